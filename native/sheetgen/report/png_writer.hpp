#pragma once
// PNG encoding of an RgbImage (PNG spec, ISO/IEC 15948): signature, IHDR
// (8-bit truecolour, no interlace), one zlib-compressed IDAT, IEND.
#include <cstdint>
#include <string>
#include <vector>

#include "sheetgen/report/rgb_image.hpp"

namespace sheetgen {

struct PngOptions {
  int compression_level = 6;  // zlib level 0 (stored) .. 9 (smallest); 6 is zlib's default
};

// The PNG file bytes. Throws std::invalid_argument naming the field when the
// image is empty, larger than 65536 px on a side or 2^26 px in all, or its pixel buffer is not
// width * height * 3 bytes.
std::vector<std::uint8_t> encode_png(const RgbImage& image, const PngOptions& options = {});

// CRC-32 of a chunk as PNG stores it: over the 4-byte type and then the data.
std::uint32_t png_chunk_crc(const std::string& type, const std::vector<std::uint8_t>& data);

// Writes encode_png(image) to `path`; throws std::runtime_error naming the path on failure.
void write_png_file(const std::string& path, const RgbImage& image, const PngOptions& options = {});

}  // namespace sheetgen
