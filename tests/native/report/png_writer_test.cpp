// PNG writer: the bytes decode (zlib inflate here, PIL in tests/python/test_report_png.py)
// to the exact pixels written, every chunk CRC checks against a bitwise CRC-32
// written independently of zlib, and bad images are refused by name.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "sheetgen/report/png_writer.hpp"

namespace sheetgen {
namespace {

std::uint32_t be32(const std::vector<std::uint8_t>& b, size_t at) {
  return (std::uint32_t(b[at]) << 24) | (std::uint32_t(b[at + 1]) << 16) | (std::uint32_t(b[at + 2]) << 8) | b[at + 3];
}

// CRC-32 bit by bit (ISO 3309 / PNG spec Annex D polynomial, reflected 0xEDB88320).
std::uint32_t bitwise_crc32(const std::uint8_t* p, size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
  }
  return c ^ 0xFFFFFFFFu;
}

struct Chunk {
  std::string type;
  std::vector<std::uint8_t> data;
  std::uint32_t stored_crc = 0, computed_crc = 0;
};

std::vector<Chunk> chunks(const std::vector<std::uint8_t>& png) {
  std::vector<Chunk> out;
  size_t at = 8;
  while (at + 12 <= png.size()) {
    const std::uint32_t len = be32(png, at);
    Chunk c;
    c.type.assign(png.begin() + at + 4, png.begin() + at + 8);
    c.data.assign(png.begin() + at + 8, png.begin() + at + 8 + len);
    c.stored_crc = be32(png, at + 8 + len);
    c.computed_crc = bitwise_crc32(png.data() + at + 4, 4 + len);
    out.push_back(c);
    at += 12 + len;
  }
  EXPECT_EQ(at, png.size()) << "trailing bytes after the last chunk";
  return out;
}

// A minimal decoder for what the writer promises: 8-bit RGB, filter 0, one IDAT stream.
RgbImage decode(const std::vector<std::uint8_t>& png) {
  const std::vector<std::uint8_t> sig = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  EXPECT_TRUE(std::equal(sig.begin(), sig.end(), png.begin()));
  const auto cs = chunks(png);
  EXPECT_GE(cs.size(), 3u);
  EXPECT_EQ(cs.front().type, "IHDR");
  EXPECT_EQ(cs.back().type, "IEND");
  RgbImage img;
  std::vector<std::uint8_t> idat;
  for (const auto& c : cs) {
    EXPECT_EQ(c.stored_crc, c.computed_crc) << c.type;
    if (c.type == "IHDR") {
      img.width_px = static_cast<int>(be32(c.data, 0));
      img.height_px = static_cast<int>(be32(c.data, 4));
      EXPECT_EQ(c.data.size(), 13u);
      EXPECT_EQ(c.data[8], 8);   // bit depth
      EXPECT_EQ(c.data[9], 2);   // truecolour
      EXPECT_EQ(c.data[12], 0);  // no interlace
    }
    if (c.type == "IDAT") idat.insert(idat.end(), c.data.begin(), c.data.end());
  }
  const size_t row = static_cast<size_t>(img.width_px) * 3 + 1;
  std::vector<std::uint8_t> raw(row * img.height_px);
  uLongf raw_len = raw.size();
  EXPECT_EQ(uncompress(raw.data(), &raw_len, idat.data(), idat.size()), Z_OK);
  EXPECT_EQ(raw_len, raw.size());
  for (int y = 0; y < img.height_px; ++y) {
    EXPECT_EQ(raw[row * y], 0) << "filter type of row " << y;
    img.pixels.insert(img.pixels.end(), raw.begin() + row * y + 1, raw.begin() + row * (y + 1));
  }
  return img;
}

RgbImage gradient(int w, int h) {
  RgbImage img(w, h, {});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.set(x, y, {std::uint8_t(x * 30), std::uint8_t(y * 40 + 1), std::uint8_t((x + y) * 7 + 200)});
  return img;
}

TEST(PngWriter, IendCrcIsTheSpecValue) {
  // Every PNG ends in 00 00 00 00 'IEND' AE 42 60 82.
  EXPECT_EQ(png_chunk_crc("IEND", {}), 0xAE426082u);
  const auto png = encode_png(gradient(2, 2));
  const std::vector<std::uint8_t> tail = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  ASSERT_GE(png.size(), tail.size());
  EXPECT_TRUE(std::equal(tail.begin(), tail.end(), png.end() - tail.size()));
}

TEST(PngWriter, ChunkCrcMatchesABitwiseCrc) {
  // IHDR of a 1 x 1 RGB image; the bitwise CRC is independent of zlib.
  const std::vector<std::uint8_t> ihdr = {0, 0, 0, 1, 0, 0, 0, 1, 8, 2, 0, 0, 0};
  std::vector<std::uint8_t> typed = {'I', 'H', 'D', 'R'};
  typed.insert(typed.end(), ihdr.begin(), ihdr.end());
  EXPECT_EQ(png_chunk_crc("IHDR", ihdr), bitwise_crc32(typed.data(), typed.size()));
  EXPECT_EQ(png_chunk_crc("IHDR", ihdr), 0x907753DEu);  // the IHDR CRC every 1x1 8-bit RGB PNG carries
}

TEST(PngWriter, RoundTripGivesTheExactPixels) {
  for (int level : {0, 6, 9}) {
    const RgbImage img = gradient(7, 5);
    const RgbImage back = decode(encode_png(img, {level}));
    EXPECT_EQ(back.width_px, 7);
    EXPECT_EQ(back.height_px, 5);
    EXPECT_EQ(back.pixels, img.pixels) << "level " << level;
    EXPECT_EQ(back.at(6, 4), (Rgb{180, 161, 14}));  // (6*30, 4*40+1, (10*7+200) mod 256)
  }
}

TEST(PngWriter, OnePixelAndOneRowImages) {
  RgbImage dot(1, 1, {12, 34, 56});
  EXPECT_EQ(decode(encode_png(dot)).pixels, dot.pixels);
  const RgbImage row = gradient(9, 1);
  EXPECT_EQ(decode(encode_png(row)).pixels, row.pixels);
}

TEST(PngWriter, RefusesBadImagesByField) {
  RgbImage empty;
  try {
    encode_png(empty);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("width_px 0"), std::string::npos) << e.what();
  }
  RgbImage short_buffer = gradient(4, 4);
  short_buffer.pixels.pop_back();
  try {
    encode_png(short_buffer);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pixels has 47 bytes, want 48"), std::string::npos) << e.what();
  }
  EXPECT_THROW(encode_png(gradient(2, 2), {10}), std::invalid_argument);
}

TEST(PngWriter, WriteFileNamesThePathOnFailure) {
  const std::string bad = "/nonexistent-dir-for-sheetgen/plot.png";
  try {
    write_png_file(bad, gradient(2, 2));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sheetgen
