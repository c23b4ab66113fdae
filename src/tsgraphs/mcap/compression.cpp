#include "tsgraphs/mcap/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <new>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs::mcap {
namespace {

/// Output of at most `size` bytes that grows as a decompressor fills it: what is allocated
/// follows what the data holds, not what a (possibly corrupt) size field claims (found by
/// fuzzing: an MCAP chunk claiming 1 GiB of garbage was zero-filled before failing).
class GrowingOutput {
 public:
  explicit GrowingOutput(std::uint64_t size) : size_(size) {}
  /// Room for more: false when `size` bytes are already there.
  bool room() {
    if (produced_ < out_.size()) return true;
    if (out_.size() == size_) return false;
    out_.resize(static_cast<std::size_t>(
        std::min<std::uint64_t>(size_, std::max<std::uint64_t>(2 * out_.size(), kFirstBytes))));
    return true;
  }
  char* next() { return out_.data() + produced_; }
  std::size_t free() const { return out_.size() - produced_; }
  void advance(std::size_t n) { produced_ += n; }
  std::uint64_t produced() const { return produced_; }
  std::string take() {
    out_.resize(produced_);
    return std::move(out_);
  }

 private:
  static constexpr std::uint64_t kFirstBytes = 1u << 16;
  std::uint64_t size_;
  std::string out_;
  std::size_t produced_ = 0;
};

using ZstdDecoder = std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)>;
using ZstdEncoder = std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)>;

ZstdDecoder zstd_decoder() {
  ZstdDecoder ctx(ZSTD_createDCtx(), ZSTD_freeDCtx);
  if (!ctx) throw std::bad_alloc();
  return ctx;
}

/// zstd frames into `out` until the input ends; the error's reason, or "" when whole frames fit.
std::string zstd_into(const char* src, std::uint64_t n, GrowingOutput& out) {
  if (n == 0) return "";  // no frame: nothing
  const ZstdDecoder ctx = zstd_decoder();
  ZSTD_inBuffer in{src, static_cast<std::size_t>(n), 0};
  // Until the input is used up and the decoder calls its last frame whole (0). With no room
  // left it is still asked (with none), as a frame's last bytes may hold no output.
  for (std::size_t ret = 1; in.pos < in.size || ret != 0;) {
    const bool space = out.room();
    ZSTD_outBuffer o{space ? out.next() : nullptr, space ? out.free() : 0, 0};
    const std::size_t used = in.pos;
    ret = ZSTD_decompressStream(ctx.get(), &o, &in);
    if (ZSTD_isError(ret)) return ZSTD_getErrorName(ret);
    out.advance(o.pos);
    if (o.pos == 0 && in.pos == used) return space ? "the data ends inside a frame" : "more data than that";
  }
  return "";
}

std::string lz4_into(const char* src, std::uint64_t n, GrowingOutput& out) {
  const auto free_ctx = [](LZ4F_dctx* c) { LZ4F_freeDecompressionContext(c); };
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw std::bad_alloc();
  const std::unique_ptr<LZ4F_dctx, decltype(free_ctx)> ctx(raw, free_ctx);
  std::size_t in_at = 0, hint = 1;
  while (in_at < n) {
    if (!out.room()) return "more data than that";
    std::size_t out_n = out.free(), in_n = static_cast<std::size_t>(n - in_at);
    hint = LZ4F_decompress(ctx.get(), out.next(), &out_n, src + in_at, &in_n, nullptr);
    if (LZ4F_isError(hint)) return LZ4F_getErrorName(hint);
    in_at += in_n;
    out.advance(out_n);
    if (in_n == 0 && out_n == 0) return "no progress";
  }
  return hint != 0 ? "the data ends inside a frame" : "";
}

}  // namespace

std::string decompress(const std::string& compression, const char* src, std::uint64_t n, std::uint64_t size,
                       const std::string& path, const std::string& where) {
  if (compression.empty()) {
    if (n != size) {
      throw input_error(path, 0,
                        where + ": uncompressed records of " + std::to_string(n) +
                            " bytes, its size field says " + std::to_string(size));
    }
    return std::string(src, n);
  }
  GrowingOutput out(size);
  std::string why;
  if (compression == "zstd") {
    why = zstd_into(src, n, out);
  } else if (compression == "lz4") {
    why = lz4_into(src, n, out);
  } else {
    throw input_error(path, 0,
                      where + ": unknown compression '" + compression + "' (expected none, lz4 or zstd)");
  }
  if (why.empty() && out.produced() != size) why = std::to_string(out.produced()) + " bytes";
  if (!why.empty()) {
    throw input_error(path, 0,
                      where + ": " + compression + " data does not decompress to its " +
                          std::to_string(size) + " bytes (" + why + ")");
  }
  return out.take();
}

std::string decompress_zstd(const char* src, std::uint64_t n, std::uint64_t max_size, const std::string& path,
                            const std::string& where) {
  GrowingOutput out(max_size);
  if (const std::string why = zstd_into(src, n, out); !why.empty()) {
    throw input_error(
        path, 0,
        where + ": zstd data that does not decompress (" +
            (why == "more data than that" ? "more than " + std::to_string(max_size) + " bytes" : why) + ")");
  }
  return out.take();
}

void decompress_zstd_file(const std::string& from, const std::string& to) {
  std::ifstream in(from, std::ios::binary);
  if (!in) throw input_error(from, 0, "cannot open file");
  std::ofstream out(to, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(to + ": cannot write the decompressed file");
  const ZstdDecoder ctx = zstd_decoder();
  std::string in_buf(ZSTD_DStreamInSize(), '\0'), out_buf(ZSTD_DStreamOutSize(), '\0');
  std::size_t ret = 0;
  std::uint64_t at = 0;
  bool any = false;
  while (in) {
    in.read(in_buf.data(), static_cast<std::streamsize>(in_buf.size()));
    ZSTD_inBuffer ib{in_buf.data(), static_cast<std::size_t>(in.gcount()), 0};
    any = any || ib.size > 0;
    while (ib.pos < ib.size) {
      ZSTD_outBuffer ob{out_buf.data(), out_buf.size(), 0};
      ret = ZSTD_decompressStream(ctx.get(), &ob, &ib);
      if (ZSTD_isError(ret)) {
        throw input_error(from, 0,
                          "zstd data that does not decompress near byte " + std::to_string(at + ib.pos) +
                              " (" + ZSTD_getErrorName(ret) + ")");
      }
      out.write(out_buf.data(), static_cast<std::streamsize>(ob.pos));
    }
    at += ib.size;
  }
  // A frame's last block may still be held: flush until the decoder says the frame is whole.
  while (ret != 0) {
    ZSTD_inBuffer ib{nullptr, 0, 0};
    ZSTD_outBuffer ob{out_buf.data(), out_buf.size(), 0};
    ret = ZSTD_decompressStream(ctx.get(), &ob, &ib);
    if (ZSTD_isError(ret) || ob.pos == 0)
      throw input_error(from, 0, "zstd data that ends inside a frame (cut off?)");
    out.write(out_buf.data(), static_cast<std::streamsize>(ob.pos));
  }
  if (!any) throw input_error(from, 0, "an empty file, not zstd data");
  if (!out) throw std::runtime_error(to + ": cannot write the decompressed file");
}

std::string compress_zstd(const std::string& in, int level) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  const std::size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), level);
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::string compress_lz4(const std::string& in) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.contentSize = in.size();
  std::string out(LZ4F_compressFrameBound(in.size(), &prefs), '\0');
  const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &prefs);
  if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(n));
  out.resize(n);
  return out;
}

void compress_zstd_file(const std::string& from, const std::string& to, int level) {
  std::ifstream in(from, std::ios::binary);
  if (!in) throw std::runtime_error(from + ": cannot open the file to compress");
  std::ofstream out(to, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(to + ": cannot write the compressed file");
  const ZstdEncoder ctx(ZSTD_createCCtx(), ZSTD_freeCCtx);
  if (!ctx) throw std::bad_alloc();
  ZSTD_CCtx_setParameter(ctx.get(), ZSTD_c_compressionLevel, level);
  std::string in_buf(ZSTD_CStreamInSize(), '\0'), out_buf(ZSTD_CStreamOutSize(), '\0');
  for (bool last = false; !last;) {
    in.read(in_buf.data(), static_cast<std::streamsize>(in_buf.size()));
    last = !in;
    ZSTD_inBuffer ib{in_buf.data(), static_cast<std::size_t>(in.gcount()), 0};
    const ZSTD_EndDirective mode = last ? ZSTD_e_end : ZSTD_e_continue;
    for (bool done = false; !done;) {
      ZSTD_outBuffer ob{out_buf.data(), out_buf.size(), 0};
      const std::size_t left = ZSTD_compressStream2(ctx.get(), &ob, &ib, mode);
      if (ZSTD_isError(left)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(left));
      out.write(out_buf.data(), static_cast<std::streamsize>(ob.pos));
      done = last ? left == 0 : ib.pos == ib.size;
    }
  }
  if (!out) throw std::runtime_error(to + ": cannot write the compressed file");
}

}  // namespace tsgraphs::mcap
