#include "tsgraphs/pipeline/scan_log.hpp"

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <utility>

namespace tsgraphs::pipeline {
namespace {

// ~280 bytes a record: 4096 hold ~1 MB, a few minutes of scans, before spilling.
constexpr std::size_t kDefaultInMemory = 4096;

std::string tmp_dir() {
  const char* dir = std::getenv("TMPDIR");
  return dir && *dir ? dir : "/tmp";
}

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error("scan records: " + what + " (the temporary file in " + tmp_dir() + ")");
}

// A record as bytes: its fixed-size fields in order, then the warning's length and text.
class Writer {
 public:
  explicit Writer(std::string* out) : out_(out) {}
  template <class T>
  void put(const T& value) {
    out_->append(reinterpret_cast<const char*>(&value), sizeof(T));
  }

 private:
  std::string* out_;
};

class Reader {
 public:
  explicit Reader(std::FILE* file) : file_(file) {}
  template <class T>
  void get(T* value) {
    if (std::fread(value, sizeof(T), 1, file_) != 1) fail("cannot read back");
  }
  void get_text(std::string* text, std::size_t n) {
    text->resize(n);
    if (n > 0 && std::fread(text->data(), 1, n, file_) != n) fail("cannot read back");
  }

 private:
  std::FILE* file_;
};

void serialise(const ScanRecord& r, std::string* out) {
  Writer w(out);
  w.put(static_cast<std::uint64_t>(r.scan_index));
  w.put(r.stamp);
  w.put(static_cast<std::int32_t>(r.keyframe));
  w.put(static_cast<std::int32_t>(r.reference_keyframe));
  const Eigen::Matrix<double, 3, 4> T = r.odom.matrix().topRows<3>();
  for (int i = 0; i < T.size(); ++i) w.put(T.data()[i]);
  w.put(static_cast<std::uint64_t>(r.num_points));
  w.put(r.prefilter_ms);
  w.put(r.ground_ms);
  w.put(static_cast<std::uint64_t>(r.num_ground_nodes));
  w.put(r.rooms_ms);
  w.put(static_cast<std::int64_t>(r.ground_tp));
  w.put(static_cast<std::int64_t>(r.ground_fp));
  w.put(static_cast<std::int64_t>(r.ground_fn));
  w.put(r.walls_ms);
  w.put(r.loop_ms);
  w.put(r.frontend_ms);
  w.put(static_cast<std::uint64_t>(r.warning.size()));
  out->append(r.warning);
}

ScanRecord deserialise(Reader& in) {
  ScanRecord r;
  std::uint64_t u = 0;
  std::int32_t i32 = 0;
  std::int64_t i64 = 0;
  in.get(&u);
  r.scan_index = static_cast<std::size_t>(u);
  in.get(&r.stamp);
  in.get(&i32);
  r.keyframe = i32;
  in.get(&i32);
  r.reference_keyframe = i32;
  Eigen::Matrix<double, 3, 4> T;
  for (int i = 0; i < T.size(); ++i) in.get(T.data() + i);
  r.odom = Pose3::Identity();
  r.odom.matrix().topRows<3>() = T;
  in.get(&u);
  r.num_points = static_cast<std::size_t>(u);
  in.get(&r.prefilter_ms);
  in.get(&r.ground_ms);
  in.get(&u);
  r.num_ground_nodes = static_cast<std::size_t>(u);
  in.get(&r.rooms_ms);
  in.get(&i64);
  r.ground_tp = static_cast<long>(i64);
  in.get(&i64);
  r.ground_fp = static_cast<long>(i64);
  in.get(&i64);
  r.ground_fn = static_cast<long>(i64);
  in.get(&r.walls_ms);
  in.get(&r.loop_ms);
  in.get(&r.frontend_ms);
  in.get(&u);
  in.get_text(&r.warning, static_cast<std::size_t>(u));
  return r;
}

}  // namespace

ScanLog::ScanLog(std::size_t in_memory) : in_memory_(in_memory > 0 ? in_memory : kDefaultInMemory) {}

ScanLog::~ScanLog() {
  if (file_) std::fclose(file_);
}

ScanLog::ScanLog(ScanLog&& other) noexcept
    : in_memory_(other.in_memory_),
      recent_(std::move(other.recent_)),
      file_(other.file_),
      spilled_(other.spilled_) {
  other.file_ = nullptr;
  other.spilled_ = 0;
  other.recent_.clear();
}

ScanLog& ScanLog::operator=(ScanLog&& other) noexcept {
  if (this != &other) {
    if (file_) std::fclose(file_);
    in_memory_ = other.in_memory_;
    recent_ = std::move(other.recent_);
    file_ = other.file_;
    spilled_ = other.spilled_;
    other.file_ = nullptr;
    other.spilled_ = 0;
    other.recent_.clear();
  }
  return *this;
}

void ScanLog::append(const ScanRecord& record) {
  if (recent_.size() >= in_memory_) spill();
  recent_.push_back(record);
}

void ScanLog::spill() {
  if (!file_) {
    file_ = std::tmpfile();  // unnamed: nothing is left behind, whatever ends the process
    if (!file_) fail("cannot create");
  }
  std::string bytes;
  for (const ScanRecord& r : recent_) serialise(r, &bytes);
  if (std::fseek(file_, 0, SEEK_END) != 0 ||
      std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    fail("cannot write (is the disk full?)");
  spilled_ += recent_.size();
  recent_.clear();
}

void ScanLog::for_each(const std::function<void(const ScanRecord&)>& visit) const {
  if (file_ && spilled_ > 0) {
    if (std::fflush(file_) != 0 || std::fseek(file_, 0, SEEK_SET) != 0) fail("cannot read back");
    Reader in(file_);
    for (std::size_t i = 0; i < spilled_; ++i) visit(deserialise(in));
  }
  for (const ScanRecord& r : recent_) visit(r);
}

}  // namespace tsgraphs::pipeline
