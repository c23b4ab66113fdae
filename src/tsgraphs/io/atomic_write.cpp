#include "tsgraphs/io/atomic_write.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"

namespace fs = std::filesystem;

namespace tsgraphs::io {
namespace {

std::string unique_suffix() {
  static std::atomic<int> counter{0};
  return ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

// Removes temporary siblings of `final_path` left by runs that were killed (their process
// no longer exists), so that killed runs leave no garbage behind for long.
void remove_stale_temporaries(const std::string& final_path) {
  const fs::path parent =
      fs::path(final_path).parent_path().empty() ? fs::path(".") : fs::path(final_path).parent_path();
  const std::string prefix = fs::path(final_path).filename().string() + ".tmp-";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const pid_t pid = static_cast<pid_t>(std::atol(rest.substr(0, rest.find('-')).c_str()));
    if (pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH)
      fs::remove_all(entry.path(), ec);
  }
}

}  // namespace

void write_file_atomic(const std::string& path, const std::string& content) {
  // Checked first: a rename onto a folder fails only after the content was written.
  if (fs::is_directory(path)) throw InputError(path + ": is a folder; give a file name to write");
  const std::string tmp = path + unique_suffix();
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot write (folder missing or not writable)");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp);
      throw std::runtime_error(path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error(path + ": cannot rename into place: " + ec.message());
  }
}

AtomicDirectory::AtomicDirectory(std::string final_path, const std::string& marker_file)
    : final_path_(fs::path(std::move(final_path)).lexically_normal().string()) {
  if (!final_path_.empty() && final_path_.back() == '/') final_path_.pop_back();
  // "/" (or "", ".." above it) names no folder that a temporary sibling could be renamed to.
  if (fs::path(final_path_).filename().empty() ||
      fs::absolute(fs::path(final_path_)).lexically_normal() == "/")
    throw InputError((final_path_.empty() ? std::string("/") : final_path_) +
                     ": not a folder to write into; give a new folder, or an earlier output to replace");
  if (fs::exists(final_path_)) {
    if (!fs::is_directory(final_path_)) throw InputError(final_path_ + ": exists and is not a folder");
    const bool empty = fs::is_empty(final_path_);
    if (!empty && !fs::exists(fs::path(final_path_) / marker_file)) {
      throw InputError(final_path_ + ": folder exists and does not hold an earlier output (no " +
                       marker_file + "); refusing to overwrite it");
    }
  }
  const fs::path parent = fs::path(final_path_).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  remove_stale_temporaries(final_path_);
  tmp_path_ = final_path_ + unique_suffix();
  if (ec || !fs::create_directories(tmp_path_, ec) || ec) {
    throw InputError(final_path_ + ": cannot create the output folder here (" +
                     (ec ? ec.message() : std::string("not writable")) + ")");
  }
}

AtomicDirectory::~AtomicDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(tmp_path_, ec);
  }
}

void AtomicDirectory::commit() {
  std::error_code ec;
  if (fs::exists(final_path_)) {
    const std::string old = final_path_ + unique_suffix();
    fs::rename(final_path_, old);
    fs::rename(tmp_path_, final_path_);
    fs::remove_all(old, ec);
  } else {
    fs::rename(tmp_path_, final_path_);
  }
  committed_ = true;
}

InputError AtomicDirectory::named_as_final(const InputError& error) const {
  std::string message = error.what();
  for (std::size_t at = message.find(tmp_path_); at != std::string::npos;
       at = message.find(tmp_path_, at + final_path_.size())) {
    message.replace(at, tmp_path_.size(), final_path_);
  }
  return InputError(message);
}

}  // namespace tsgraphs::io
