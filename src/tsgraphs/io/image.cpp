#include "tsgraphs/io/image.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/text_file.hpp"

namespace tsgraphs::io {
namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr int kMaxPgmValue = 65535;  // the netpbm format's largest maxval
constexpr int kMaxSide = 1 << 20;    // pixels a side (libpng's own limit is 2^31)

std::string size_text(long long w, long long h) { return std::to_string(w) + " x " + std::to_string(h); }

void check_size(long long w, long long h, const std::string& name) {
  if (w <= 0 || h <= 0)
    throw input_error(name, 0, "image size " + size_text(w, h) + ": must be at least 1 x 1");
  if (w > kMaxSide || h > kMaxSide || w * h > kMaxImagePixels)
    throw input_error(name, 0,
                      "image size " + size_text(w, h) + " is absurd (more than " +
                          std::to_string(kMaxImagePixels) + " pixels)");
}

/// A value of 0..maxval as 0..255, rounded.
std::uint8_t scale_to_8bit(unsigned v, unsigned maxval) {
  return maxval == 255 ? static_cast<std::uint8_t>(v)
                       : static_cast<std::uint8_t>((v * 255u + maxval / 2) / maxval);
}

/// The netpbm header and plain raster: whitespace and '#' comments between numbers.
class PgmReader {
 public:
  PgmReader(const std::string& bytes, const std::string& name) : b_(bytes), name_(name) {}

  Image read() {
    if (b_.size() < 2 || b_[0] != 'P') throw input_error(name_, 0, "not a PGM file (no 'P' magic number)");
    const char kind = b_[1];
    if (kind == '1' || kind == '3' || kind == '4' || kind == '6' || kind == '7')
      throw input_error(name_, 0,
                        std::string("a P") + kind + " netpbm image: only PGM (P5, P2) and PNG maps are read");
    if (kind != '5' && kind != '2')
      throw input_error(name_, 0, "not a PGM file (magic number is not P5 or P2)");
    pos_ = 2;
    if (pos_ < b_.size() && !is_space(b_[pos_]) && b_[pos_] != '#')
      throw input_error(name_, 0, "PGM header: no whitespace after the magic number");
    const long long w = number("width");
    const long long h = number("height");
    const long long maxval = number("maxval");
    check_size(w, h, name_);
    if (maxval < 1 || maxval > kMaxPgmValue)
      throw input_error(name_, 0, "PGM header: maxval " + std::to_string(maxval) + " must lie in 1..65535");
    Image img;
    img.width = static_cast<int>(w);
    img.height = static_cast<int>(h);
    img.channels = 1;
    const std::size_t n = static_cast<std::size_t>(w * h);
    img.samples.resize(n);
    const unsigned mv = static_cast<unsigned>(maxval);
    if (kind == '5') {
      // Exactly one whitespace character separates maxval from the raster.
      if (pos_ >= b_.size()) throw truncated(0, n);
      if (!is_space(b_[pos_])) throw input_error(name_, 0, "PGM header: no whitespace after maxval");
      ++pos_;
      const std::size_t bytes_per = maxval > 255 ? 2 : 1;
      const std::size_t available = b_.size() - pos_;
      if (available < n * bytes_per) throw truncated(available / bytes_per, n);
      const auto* p = reinterpret_cast<const unsigned char*>(b_.data() + pos_);
      for (std::size_t i = 0; i < n; ++i) {
        const unsigned v = bytes_per == 2 ? (static_cast<unsigned>(p[2 * i]) << 8 | p[2 * i + 1]) : p[i];
        if (v > mv) throw bad_value(i, w, v, mv);
        img.samples[i] = scale_to_8bit(v, mv);
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        skip_space_and_comments();
        if (pos_ >= b_.size()) throw truncated(i, n);
        const long long v = number("pixel " + std::to_string(i));
        if (v > maxval) throw bad_value(i, w, static_cast<unsigned>(v), mv);
        img.samples[i] = scale_to_8bit(static_cast<unsigned>(v), mv);
      }
    }
    return img;
  }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
  }

  void skip_space_and_comments() {
    while (pos_ < b_.size()) {
      if (is_space(b_[pos_])) {
        ++pos_;
      } else if (b_[pos_] == '#') {
        while (pos_ < b_.size() && b_[pos_] != '\n' && b_[pos_] != '\r') ++pos_;
      } else {
        break;
      }
    }
  }

  /// A decimal number (after whitespace and comments); `what` names it in messages.
  long long number(const std::string& what) {
    skip_space_and_comments();
    if (pos_ >= b_.size()) throw input_error(name_, 0, "PGM header ends before its " + what);
    long long v = 0;
    std::size_t digits = 0;
    while (pos_ < b_.size() && b_[pos_] >= '0' && b_[pos_] <= '9') {
      v = v * 10 + (b_[pos_] - '0');
      if (v > (1LL << 40)) throw input_error(name_, 0, "PGM: " + what + " is absurdly large");
      ++pos_;
      ++digits;
    }
    if (digits == 0) {
      const char c = b_[pos_];
      const std::string shown = (c >= 32 && c < 127)
                                    ? std::string("'") + c + "'"
                                    : "byte " + std::to_string(static_cast<unsigned char>(c));
      throw input_error(name_, 0, "PGM: " + what + " is not a number (found " + shown + ")");
    }
    if (pos_ < b_.size() && !is_space(b_[pos_]) && b_[pos_] != '#')
      throw input_error(name_, 0, "PGM: " + what + " is not a number");
    return v;
  }

  InputError truncated(std::size_t found, std::size_t expected) const {
    return input_error(
        name_, 0,
        "truncated PGM: " + std::to_string(found) + " of " + std::to_string(expected) + " pixels present");
  }
  InputError bad_value(std::size_t i, long long width, unsigned v, unsigned maxval) const {
    const std::size_t w = static_cast<std::size_t>(width);
    return input_error(name_, 0,
                       "PGM pixel at column " + std::to_string(i % w) + ", row " + std::to_string(i / w) +
                           ": value " + std::to_string(v) + " exceeds maxval " + std::to_string(maxval));
  }

  const std::string& b_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

// ---- PNG through libpng. Its errors longjmp back to a setjmp; the functions that arm it hold
// no object with a destructor, so nothing is skipped on the way back.

struct PngSource {
  const unsigned char* data;
  std::size_t size;
  std::size_t pos;
  char message[256];
};

void png_error_to_message(png_structp png, png_const_charp msg) {
  auto* src = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(src->message, sizeof(src->message), "%s", msg);
  png_longjmp(png, 1);
}

void png_ignore_warning(png_structp, png_const_charp) {}

void png_read_from_memory(png_structp png, png_bytep out, png_size_t n) {
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (src->size - src->pos < n) png_error(png, "truncated file (the data ends early)");
  std::memcpy(out, src->data + src->pos, n);
  src->pos += n;
}

/// Owns libpng's read structures.
struct PngRead {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngRead() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

/// Reads the header and sets the 8-bit expansions; false (and src->message) on a libpng error.
bool png_read_header(PngRead* r, PngSource* src, png_uint_32* w, png_uint_32* h, int* channels) {
  if (setjmp(png_jmpbuf(r->png))) return false;
  png_set_read_fn(r->png, src, png_read_from_memory);
  png_set_user_limits(r->png, kMaxSide, kMaxSide);
  png_read_info(r->png, r->info);
  const int color_type = png_get_color_type(r->png, r->info);
  const int bit_depth = png_get_bit_depth(r->png, r->info);
  // As map_server's reader (SDL_image): 16-bit samples keep their high byte, grey below 8 bits
  // is scaled to 0..255, a tRNS colour key is no alpha channel. Palettes become their colours
  // (SDL_image hands map_server the palette index, which is the grey only for a grey ramp).
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(r->png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(r->png);
  if (bit_depth == 16) png_set_strip_16(r->png);
  png_set_interlace_handling(r->png);
  png_read_update_info(r->png, r->info);
  *w = png_get_image_width(r->png, r->info);
  *h = png_get_image_height(r->png, r->info);
  *channels = png_get_channels(r->png, r->info);
  return true;
}

bool png_read_pixels(PngRead* r, png_bytepp rows) {
  if (setjmp(png_jmpbuf(r->png))) return false;
  png_read_image(r->png, rows);
  return true;
}

struct PngSink {
  std::string* out;
  char message[256];
};

void png_write_to_string(png_structp png, png_bytep data, png_size_t n) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  sink->out->append(reinterpret_cast<const char*>(data), n);
}
void png_flush_nothing(png_structp) {}
void png_write_error(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof(sink->message), "%s", msg);
  png_longjmp(png, 1);
}

bool png_write_all(png_structp png, png_infop info, PngSink* sink, const Image* img, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, sink, png_write_to_string, png_flush_nothing);
  static const int kTypes[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_IHDR(png, info, img->width, img->height, 8, kTypes[img->channels], PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

Image decode_pgm(const std::string& bytes, const std::string& name) { return PgmReader(bytes, name).read(); }

Image decode_png(const std::string& bytes, const std::string& name) {
  if (bytes.size() < sizeof(kPngSignature) ||
      std::memcmp(bytes.data(), kPngSignature, sizeof(kPngSignature)) != 0)
    throw input_error(name, 0, "not a PNG file (bad signature)");
  PngSource src{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 0, {0}};
  PngRead r;
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, png_error_to_message, png_ignore_warning);
  if (r.png == nullptr) throw std::runtime_error("libpng: cannot create a read structure");
  r.info = png_create_info_struct(r.png);
  if (r.info == nullptr) throw std::runtime_error("libpng: cannot create an info structure");
  png_uint_32 w = 0, h = 0;
  int channels = 0;
  if (!png_read_header(&r, &src, &w, &h, &channels))
    throw input_error(name, 0, std::string("bad PNG: ") + src.message);
  check_size(w, h, name);
  if (channels < 1 || channels > 4)
    throw input_error(name, 0, "PNG with " + std::to_string(channels) + " channels");
  Image img;
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
  img.channels = channels;
  img.samples.resize(static_cast<std::size_t>(w) * h * channels);
  std::vector<png_bytep> rows(h);
  for (png_uint_32 y = 0; y < h; ++y)
    rows[y] = img.samples.data() + static_cast<std::size_t>(y) * w * channels;
  if (!png_read_pixels(&r, rows.data())) throw input_error(name, 0, std::string("bad PNG: ") + src.message);
  return img;
}

Image decode_image(const std::string& bytes, const std::string& name) {
  if (bytes.empty()) throw input_error(name, 0, "empty file (not an image)");
  if (bytes.size() >= sizeof(kPngSignature) &&
      std::memcmp(bytes.data(), kPngSignature, sizeof(kPngSignature)) == 0)
    return decode_png(bytes, name);
  if (bytes[0] == 'P' && bytes.size() >= 2 && bytes[1] >= '1' && bytes[1] <= '7')
    return decode_pgm(bytes, name);
  if (bytes.size() >= 4 && bytes.compare(0, 4, "\x89PNG") == 0)
    return decode_png(bytes, name);  // a damaged signature
  throw input_error(name, 0, "not a PGM or PNG image (unknown first bytes)");
}

Image read_image(const std::string& path) {
  return decode_image(read_text_file(path, "no such image file"), path);
}

std::string encode_pgm(const Image& image) {
  if (image.channels != 1) throw std::invalid_argument("encode_pgm: a PGM has one channel");
  std::string out = "P5\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  out.append(reinterpret_cast<const char*>(image.samples.data()), image.samples.size());
  return out;
}

std::string encode_png(const Image& image) {
  if (image.channels < 1 || image.channels > 4 || image.width < 1 || image.height < 1 ||
      image.samples.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    throw std::invalid_argument("encode_png: bad image");
  std::string out;
  PngSink sink{&out, {0}};
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_write_error, png_ignore_warning);
  if (png == nullptr) throw std::runtime_error("libpng: cannot create a write structure");
  png_infop info = png_create_info_struct(png);
  std::vector<png_bytep> rows(image.height);
  for (int y = 0; y < image.height; ++y)
    rows[y] = const_cast<png_bytep>(image.samples.data()) +
              static_cast<std::size_t>(y) * image.width * image.channels;
  const bool ok = info != nullptr && png_write_all(png, info, &sink, &image, rows.data());
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!ok) throw std::runtime_error(std::string("libpng: ") + sink.message);
  return out;
}

std::vector<std::uint8_t> luma(const Image& image) {
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  std::vector<std::uint8_t> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = image.samples.data() + i * image.channels;
    if (image.channels <= 2) {
      out[i] = p[0];
    } else {
      // OpenCV's fixed-point RGB to grey: 0.299 R + 0.587 G + 0.114 B in 14 bits, rounded.
      out[i] = static_cast<std::uint8_t>((p[0] * 4899u + p[1] * 9617u + p[2] * 1868u + (1u << 13)) >> 14);
    }
  }
  return out;
}

}  // namespace tsgraphs::io
