#pragma once
/// Compressed bytes as recordings hold them: zstd (Debian's libzstd) and lz4 frames (liblz4).
/// MCAP's chunks and rosbag2's own compression (a whole file, or each message) share these.
/// What is allocated follows what the data decompresses to, never more than the size the
/// caller allows: a corrupt size word costs an error, not its gigabytes.
#include <cstdint>
#include <string>

namespace tsgraphs::mcap {

/// `src` (n bytes) decompressed to exactly `size` bytes: `compression` is "" (stored as is),
/// "lz4" or "zstd", as an MCAP chunk names it. InputError naming `path` and `where` otherwise.
std::string decompress(const std::string& compression, const char* src, std::uint64_t n, std::uint64_t size,
                       const std::string& path, const std::string& where);

/// zstd frames (n bytes) decompressed to whatever they hold, at most `max_size` bytes.
std::string decompress_zstd(const char* src, std::uint64_t n, std::uint64_t max_size, const std::string& path,
                            const std::string& where);

/// A zstd-compressed file decompressed into `to` (created or truncated), streamed: any size.
/// InputError naming `from` for data that is not zstd or ends inside a frame.
void decompress_zstd_file(const std::string& from, const std::string& to);

/// The zstd level recordings are written with: the fastest (bags are written once by simulate,
/// read many times), and rosbag2's own default.
constexpr int kZstdLevel = 1;

/// zstd at `level`, one frame that records its content size.
std::string compress_zstd(const std::string& in, int level = kZstdLevel);

/// One lz4 frame that records its content size.
std::string compress_lz4(const std::string& in);

/// A file compressed with zstd at `level` into `to` (created or truncated), streamed.
void compress_zstd_file(const std::string& from, const std::string& to, int level = kZstdLevel);

}  // namespace tsgraphs::mcap
