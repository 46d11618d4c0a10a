#pragma once
// An 8-bit RGB raster: what the canvas draws into and the PNG writer encodes.
#include <cstdint>
#include <vector>

namespace sheetgen {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb& o) const { return !(*this == o); }
};

struct RgbImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> pixels;  // #height by #width by 3 (r, g, b), rows top to bottom

  RgbImage() = default;
  RgbImage(int width, int height, Rgb fill) : width_px(width), height_px(height) {
    pixels.resize(static_cast<size_t>(width > 0 ? width : 0) * (height > 0 ? height : 0) * 3);
    for (size_t i = 0; i < pixels.size(); i += 3) {
      pixels[i] = fill.r;
      pixels[i + 1] = fill.g;
      pixels[i + 2] = fill.b;
    }
  }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_px && y < height_px; }
  // Pixel (x, y), x to the right, y down from the top-left corner; must be inside.
  Rgb at(int x, int y) const {
    const size_t i = (static_cast<size_t>(y) * width_px + x) * 3;
    return {pixels[i], pixels[i + 1], pixels[i + 2]};
  }
  void set(int x, int y, Rgb c) {
    const size_t i = (static_cast<size_t>(y) * width_px + x) * 3;
    pixels[i] = c.r;
    pixels[i + 1] = c.g;
    pixels[i + 2] = c.b;
  }
};

}  // namespace sheetgen
