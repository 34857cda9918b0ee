#include "oblique/report/picture.h"

#include <png.h>

#include <algorithm>

namespace oblique::report {

namespace {

void fill_rgba(std::uint8_t* p, std::uint32_t rgba) {
  p[0] = static_cast<std::uint8_t>(rgba >> 24);
  p[1] = static_cast<std::uint8_t>(rgba >> 16);
  p[2] = static_cast<std::uint8_t>(rgba >> 8);
  p[3] = static_cast<std::uint8_t>(rgba);
}

void append_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void no_flush(png_structp) {}

/// Copies `p` into `out` with its top left corner at (left, top).
void paste(Picture& out, const Picture& p, int left, int top) {
  for (int y = 0; y < p.height; ++y)
    std::copy(p.at(0, y), p.at(0, y) + static_cast<std::size_t>(p.width) * 4,
              out.at(left, top + y));
}

}  // namespace

Picture::Picture(int w, int h, std::uint32_t fill)
    : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4) {
  for (std::size_t i = 0; i < rgba.size(); i += 4) fill_rgba(&rgba[i], fill);
}

std::string png_bytes(const Picture& picture) {
  if (picture.width <= 0 || picture.height <= 0 ||
      picture.rgba.size() != static_cast<std::size_t>(picture.width) * picture.height * 4)
    return {};
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return {};
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return {};
  }
  png_set_write_fn(png, &out, append_bytes, no_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(picture.width),
               static_cast<png_uint_32>(picture.height), 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < picture.height; ++y)
    png_write_row(png, const_cast<png_bytep>(picture.at(0, y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

std::string base64(std::string_view bytes) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{static_cast<std::uint8_t>(bytes[i])} << 16) |
                            (std::uint32_t{static_cast<std::uint8_t>(bytes[i + 1])} << 8) |
                            std::uint32_t{static_cast<std::uint8_t>(bytes[i + 2])};
    for (int k = 3; k >= 0; --k) out += kDigits[(v >> (6 * k)) & 63];
  }
  const std::size_t left = bytes.size() - i;
  if (left > 0) {
    std::uint32_t v = std::uint32_t{static_cast<std::uint8_t>(bytes[i])} << 16;
    if (left == 2) v |= std::uint32_t{static_cast<std::uint8_t>(bytes[i + 1])} << 8;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += left == 2 ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

Picture side_by_side(const std::vector<const Picture*>& pictures, int gap,
                     std::uint32_t background) {
  int width = 0, height = 0;
  for (const Picture* p : pictures) {
    width += p->width + (width > 0 ? gap : 0);
    height = std::max(height, p->height);
  }
  Picture out(width, height, background);
  int left = 0;
  for (const Picture* p : pictures) {
    paste(out, *p, left, (height - p->height) / 2);
    left += p->width + gap;
  }
  return out;
}

Picture stacked(const std::vector<const Picture*>& pictures, std::uint32_t background) {
  int width = 0, height = 0;
  for (const Picture* p : pictures) {
    width = std::max(width, p->width);
    height += p->height;
  }
  Picture out(width, height, background);
  int top = 0;
  for (const Picture* p : pictures) {
    paste(out, *p, (width - p->width) / 2, top);
    top += p->height;
  }
  return out;
}

}  // namespace oblique::report
