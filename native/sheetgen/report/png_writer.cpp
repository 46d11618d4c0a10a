#include "sheetgen/report/png_writer.hpp"

#include <zlib.h>

#include <fstream>
#include <stdexcept>

namespace sheetgen {
namespace {

void put_u32_be(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

// length, type, data, CRC(type + data)
void put_chunk(std::vector<std::uint8_t>& out, const std::string& type, const std::vector<std::uint8_t>& data) {
  put_u32_be(out, static_cast<std::uint32_t>(data.size()));
  out.insert(out.end(), type.begin(), type.end());
  out.insert(out.end(), data.begin(), data.end());
  put_u32_be(out, png_chunk_crc(type, data));
}

}  // namespace

std::uint32_t png_chunk_crc(const std::string& type, const std::vector<std::uint8_t>& data) {
  // zlib's crc32 is the CRC of the PNG spec (polynomial 0xEDB88320, pre- and post-inverted).
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, reinterpret_cast<const Bytef*>(type.data()), static_cast<uInt>(type.size()));
  if (!data.empty()) crc = crc32(crc, data.data(), static_cast<uInt>(data.size()));
  return static_cast<std::uint32_t>(crc);
}

std::vector<std::uint8_t> encode_png(const RgbImage& image, const PngOptions& options) {
  constexpr int max_side_px = 1 << 16;             // PNG allows 2^31 - 1; a plot never needs more
  constexpr long long max_area_px = 1LL << 26;      // 64 Mpx: raw scanlines stay far below zlib's 32-bit sizes
  if (image.width_px <= 0 || image.width_px > max_side_px)
    throw std::invalid_argument("encode_png: width_px " + std::to_string(image.width_px) + " is not in 1.." +
                                std::to_string(max_side_px));
  if (image.height_px <= 0 || image.height_px > max_side_px)
    throw std::invalid_argument("encode_png: height_px " + std::to_string(image.height_px) + " is not in 1.." +
                                std::to_string(max_side_px));
  if (static_cast<long long>(image.width_px) * image.height_px > max_area_px)
    throw std::invalid_argument("encode_png: width_px * height_px " + std::to_string(image.width_px) + " * " +
                                std::to_string(image.height_px) + " is over " + std::to_string(max_area_px) + " px");
  const size_t row_bytes = static_cast<size_t>(image.width_px) * 3;
  if (image.pixels.size() != row_bytes * image.height_px)
    throw std::invalid_argument("encode_png: pixels has " + std::to_string(image.pixels.size()) + " bytes, want " +
                                std::to_string(row_bytes * image.height_px) + " (width * height * 3)");
  if (options.compression_level < 0 || options.compression_level > 9)
    throw std::invalid_argument("encode_png: compression_level " + std::to_string(options.compression_level) +
                                " is not in 0..9");

  // Scanlines, each led by its filter type; 0 (None) everywhere: plots are
  // mostly flat colour, which deflate handles well without prediction.
  std::vector<std::uint8_t> raw;
  raw.reserve((row_bytes + 1) * image.height_px);
  for (int y = 0; y < image.height_px; ++y) {
    raw.push_back(0);
    const auto row = image.pixels.begin() + static_cast<std::ptrdiff_t>(row_bytes * y);
    raw.insert(raw.end(), row, row + static_cast<std::ptrdiff_t>(row_bytes));
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> packed(packed_size);
  if (compress2(packed.data(), &packed_size, raw.data(), static_cast<uLong>(raw.size()), options.compression_level) != Z_OK)
    throw std::runtime_error("encode_png: zlib compress2 failed");
  packed.resize(packed_size);

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  put_u32_be(ihdr, static_cast<std::uint32_t>(image.width_px));
  put_u32_be(ihdr, static_cast<std::uint32_t>(image.height_px));
  ihdr.push_back(8);  // bit depth
  ihdr.push_back(2);  // colour type: truecolour (RGB)
  ihdr.push_back(0);  // compression: deflate
  ihdr.push_back(0);  // filter method 0
  ihdr.push_back(0);  // no interlace
  put_chunk(png, "IHDR", ihdr);
  put_chunk(png, "IDAT", packed);
  put_chunk(png, "IEND", {});
  return png;
}

void write_png_file(const std::string& path, const RgbImage& image, const PngOptions& options) {
  const std::vector<std::uint8_t> bytes = encode_png(image, options);
  std::ofstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot open " + path + " for writing");
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  f.close();  // a full disk often shows only when the buffer is flushed
  if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace sheetgen
