#include "tsgraphs/ros2_bag/cdr.hpp"

#include <cstring>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::ros2_bag {

// The encapsulation header, and where the alignment is counted from.
constexpr std::size_t kHeaderBytes = 4;

CdrReader::CdrReader(const std::string& bytes, std::string where) : bytes_(bytes), where_(std::move(where)) {
  if (bytes.size() < kHeaderBytes)
    throw input_error(where_, 0,
                      "CDR message of " + std::to_string(bytes.size()) + " bytes: no encapsulation header");
  if (bytes[0] != 0 || (bytes[1] != 0 && bytes[1] != 1)) {
    throw input_error(where_, 0,
                      "CDR encapsulation " + std::to_string(static_cast<unsigned char>(bytes[0])) + " " +
                          std::to_string(static_cast<unsigned char>(bytes[1])) +
                          ": not plain CDR (0 0 big-endian or 0 1 little-endian)");
  }
  little_ = bytes[1] == 1;
}

void CdrReader::need(std::size_t n, const char* field) const {
  if (n > bytes_.size() - at_) {
    throw input_error(where_, 0,
                      std::string("CDR field ") + field + " (" + std::to_string(n) + " bytes at byte " +
                          std::to_string(at_) + ") runs past the message's end (" +
                          std::to_string(bytes_.size()) + " bytes)");
  }
}

void CdrReader::align(std::size_t n) {
  const std::size_t offset = (at_ - kHeaderBytes) % n;
  if (offset != 0) at_ = std::min(bytes_.size(), at_ + (n - offset));
}

template <class T>
T CdrReader::number(const char* field) {
  align(sizeof(T));
  need(sizeof(T), field);
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    const auto b =
        static_cast<T>(static_cast<unsigned char>(bytes_[at_ + (little_ ? i : sizeof(T) - 1 - i)]));
    v |= static_cast<T>(b << (8 * i));
  }
  at_ += sizeof(T);
  return v;
}

std::uint8_t CdrReader::u8(const char* field) {
  need(1, field);
  return static_cast<std::uint8_t>(bytes_[at_++]);
}

double CdrReader::f64(const char* field) {
  const std::uint64_t bits = number<std::uint64_t>(field);
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::string CdrReader::string(const char* field) {
  const std::uint32_t n = number<std::uint32_t>(field);
  need(n, field);
  std::string s(bytes_.data() + at_, n);
  at_ += n;
  if (!s.empty() && s.back() == '\0') s.pop_back();  // the length counts the terminating NUL
  return s;
}

std::uint32_t CdrReader::sequence(const char* field, std::size_t min_element_bytes) {
  const std::uint32_t n = number<std::uint32_t>(field);
  if (min_element_bytes > 0 && n > (bytes_.size() - at_) / min_element_bytes) {
    throw input_error(where_, 0,
                      std::string("CDR sequence ") + field + " of " + std::to_string(n) +
                          " elements at byte " + std::to_string(at_) + " runs past the message's end (" +
                          std::to_string(bytes_.size()) + " bytes)");
  }
  return n;
}

std::size_t CdrReader::skip(std::size_t n, const char* field) {
  need(n, field);
  const std::size_t start = at_;
  at_ += n;
  return start;
}

void CdrWriter::align(std::size_t n) {
  while ((bytes_.size() - kHeaderBytes) % n != 0) bytes_.push_back('\0');
}

template <class T>
void CdrWriter::number(T v) {
  align(sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) bytes_.push_back(static_cast<char>(v >> (8 * i)));
}

void CdrWriter::f64(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  number(bits);
}

void CdrWriter::string(const std::string& v) {
  number(static_cast<std::uint32_t>(v.size() + 1));
  bytes_ += v;
  bytes_.push_back('\0');
}

// The widths the header's inline accessors use.
template std::uint16_t CdrReader::number<std::uint16_t>(const char*);
template std::uint32_t CdrReader::number<std::uint32_t>(const char*);
template std::uint64_t CdrReader::number<std::uint64_t>(const char*);
template void CdrWriter::number<std::uint32_t>(std::uint32_t);

}  // namespace tsgraphs::ros2_bag
