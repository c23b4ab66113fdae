#pragma once
/// Text from a file quoted in a message: the promise of one clear line (docs/reliability.md)
/// holds only if no raw byte of a binary file reaches the terminal or the log.
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace tsgraphs {

/// Bytes of a file's text a message quotes at most; longer text is cut, and "..." says so.
inline constexpr std::size_t kMaxQuotedBytes = 40;
/// A path a message quotes is cut only beyond this (Linux's PATH_MAX): a longer one names no file.
inline constexpr std::size_t kMaxQuotedPathBytes = 4096;

/// `text` as a message may quote it: printable ASCII as it is, every other byte (control
/// characters, tabs, line breaks, bytes above 0x7e) as \xNN, and a backslash as \\, so that two
/// texts stay told apart; at most `max_bytes` of `text`, then "...".
inline std::string printable(std::string_view text, std::size_t max_bytes = kMaxQuotedBytes) {
  constexpr unsigned char kFirstPrintable = 0x20, kLastPrintable = 0x7e;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\\') {
      out += "\\\\";
    } else if (c >= kFirstPrintable && c <= kLastPrintable) {
      out += static_cast<char>(c);
    } else {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

}  // namespace tsgraphs
