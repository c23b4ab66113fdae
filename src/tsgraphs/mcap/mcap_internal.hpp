#pragma once
/// What the MCAP reader (mcap_reader.cpp) and writer (mcap_writer.cpp) share: the magic, the
/// opcodes and the CRC.
#include <zlib.h>

#include <cstddef>
#include <cstdint>

namespace tsgraphs::mcap::internal {

constexpr char kMagic[] = "\x89MCAP0\r\n";
constexpr std::uint64_t kMagicBytes = 8;
constexpr std::uint64_t kFooterContentBytes = 20;  // summary_start, summary_offset_start, summary_crc

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

inline std::uint32_t crc_of(const char* p, std::size_t n, std::uint32_t crc = 0) {
  return static_cast<std::uint32_t>(::crc32_z(crc, reinterpret_cast<const Bytef*>(p), n));
}

}  // namespace tsgraphs::mcap::internal
