#pragma once
/// Outputs that appear whole or not at all: write to a temporary sibling, then rename.
#include <string>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::io {

/// Writes `content` to `path` through a temporary file in the same folder and a rename.
/// Throws an InputError naming the path when it cannot create it (missing folder, no
/// permission) and std::runtime_error when a write fails half way (a full disk).
void write_file_atomic(const std::string& path, const std::string& content);

/// A folder built under a temporary name next to its final place and renamed there by
/// `commit()`. Destroying it uncommitted removes the temporary folder, so a failed or killed
/// run never leaves a folder that looks complete under the final name.
class AtomicDirectory {
 public:
  /// `final_path` may exist if it is empty or holds a previous output with `marker_file`
  /// (it is then replaced on commit); anything else is refused with an InputError, so that
  /// no unrelated folder is overwritten. A place where no folder can be made is an InputError.
  AtomicDirectory(std::string final_path, const std::string& marker_file);
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  /// The temporary folder to write into.
  const std::string& path() const { return tmp_path_; }
  const std::string& final_path() const { return final_path_; }
  /// Moves the temporary folder to the final path (replacing an earlier output).
  void commit();
  /// `error` with the temporary folder's name replaced by the final one: an error met while
  /// writing (or reading back) the outputs names the folder the user asked for, not ours.
  InputError named_as_final(const InputError& error) const;

 private:
  std::string final_path_;
  std::string tmp_path_;
  bool committed_ = false;
};

}  // namespace tsgraphs::io
