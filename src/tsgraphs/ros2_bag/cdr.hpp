#pragma once
/// CDR as ROS 2 serializes messages (XCDR1, "plain CDR"): a 4-byte encapsulation header
/// (0x00 0x00 big-endian, 0x00 0x01 little-endian, then two option bytes), then each value
/// aligned to its own size (8 at most) counted from the end of the header; strings are a
/// uint32 length that counts a terminating NUL, sequences a uint32 count.
#include <cstddef>
#include <cstdint>
#include <string>

namespace tsgraphs::ros2_bag {

/// Reads one message. Every length is checked against the bytes left before it is used: a
/// message cut short or claiming more than it holds is an InputError naming `where` and the
/// field.
class CdrReader {
 public:
  CdrReader(const std::string& bytes, std::string where);
  bool little_endian() const { return little_; }

  std::uint8_t u8(const char* field);
  bool boolean(const char* field) { return u8(field) != 0; }
  std::uint16_t u16(const char* field) { return number<std::uint16_t>(field); }
  std::uint32_t u32(const char* field) { return number<std::uint32_t>(field); }
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(number<std::uint32_t>(field)); }
  std::uint64_t u64(const char* field) { return number<std::uint64_t>(field); }
  double f64(const char* field);
  std::string string(const char* field);
  /// A sequence's element count, checked against the bytes left at `min_element_bytes` each.
  std::uint32_t sequence(const char* field, std::size_t min_element_bytes);
  /// Skips `n` raw bytes (a uint8[] body); returns where they start in the message.
  std::size_t skip(std::size_t n, const char* field);
  std::size_t position() const { return at_; }

 private:
  template <class T>
  T number(const char* field);
  void align(std::size_t n);
  void need(std::size_t n, const char* field) const;

  const std::string& bytes_;
  std::string where_;
  std::size_t at_ = 4;
  bool little_ = true;
};

/// Writes one little-endian message (encapsulation 0x00 0x01 0x00 0x00).
class CdrWriter {
 public:
  CdrWriter() : bytes_("\x00\x01\x00\x00", 4) {}
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void u32(std::uint32_t v) { number(v); }
  void i32(std::int32_t v) { number(static_cast<std::uint32_t>(v)); }
  void f64(double v);
  void string(const std::string& v);
  void sequence(std::uint32_t count) { u32(count); }
  void raw(const std::string& v) { bytes_ += v; }
  const std::string& bytes() const { return bytes_; }

 private:
  template <class T>
  void number(T v);
  void align(std::size_t n);
  std::string bytes_;
};

}  // namespace tsgraphs::ros2_bag
