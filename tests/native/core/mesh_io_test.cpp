#include "sheetgen/core/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "sheetgen/core/input_error.hpp"

namespace sheetgen {
namespace {

TEST(MeshIo, ObjPolygonsNegativeIndicesAndSlashes) {
  const TriangleMesh m = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -4 -3 -2\n", "t.obj");
  ASSERT_EQ(m.vertices.size(), 4u);
  ASSERT_EQ(m.triangles.size(), 3u);  // quad fan (2) + one triangle
  EXPECT_NEAR(m.area(), 1.0 + 0.5, 1e-12);
}

TEST(MeshIo, ObjErrorsNameTheLine) {
  try {
    parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 5\n", "t.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "t.obj: line 3: face index 5 is out of range (2 vertices so far).");
  }
}

std::string binary_ply(bool big_endian) {
  std::string h = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](const void* p, size_t n) {
    std::string b(static_cast<const char*>(p), n);
    if (big_endian) std::reverse(b.begin(), b.end());
    h += b;
  };
  const float v[9] = {0, 0, 0, 2, 0, 0, 0, 3, 0};
  for (float f : v) put(&f, 4);
  const unsigned char n = 3;
  h += static_cast<char>(n);
  for (int i : {0, 1, 2}) put(&i, 4);
  return h;
}

TEST(MeshIo, PlyAsciiAndBinaryBothEndians) {
  const std::string ascii =
      "ply\nformat ascii 1.0\ncomment x\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 255\n2 0 0 0\n0 3 0 9\n3 0 1 2\n";
  for (const std::string& bytes : {ascii, binary_ply(false), binary_ply(true)}) {
    const TriangleMesh m = parse_ply(bytes, "t.ply");
    ASSERT_EQ(m.triangles.size(), 1u);
    EXPECT_NEAR(m.area(), 3.0, 1e-12);  // 0.5 * 2 * 3
  }
}

TEST(MeshIo, TruncatedPlyIsAnError) {
  const std::string bytes = binary_ply(false);
  for (size_t cut : {size_t(20), bytes.size() - 30, bytes.size() - 1}) {
    EXPECT_THROW(parse_ply(bytes.substr(0, cut), "t.ply"), InputError) << cut;
  }
}

}  // namespace
}  // namespace sheetgen
