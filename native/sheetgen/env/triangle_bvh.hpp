#pragma once
// A bounding-volume hierarchy over triangles, for "which triangles come near
// this box?" (the exact clearance of a tab, docs/environment.md "Exact tab
// clearance"). Embree answers rays and spheres; a tab is a long thin plate,
// whose bounding box is much tighter than its bounding sphere, so we keep a
// small tree of our own for box queries.
#include <array>
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

class TriangleBvh {
 public:
  TriangleBvh() = default;
  // Triangles by their corners (m); their index in this list is what queries return.
  explicit TriangleBvh(std::vector<std::array<Vec3, 3>> triangles);

  int size() const { return static_cast<int>(triangles_.size()); }
  const std::array<Vec3, 3>& triangle(int i) const { return triangles_[i]; }

  // Appends to `out` every triangle whose bounding box meets `box`. Stops and
  // returns false as soon as more than `cap` were found (out is then partial).
  bool overlapping(const BoundingBox& box, std::vector<int>& out, int cap) const;

 private:
  struct Node {
    BoundingBox box;
    int first = 0, count = 0;  // leaf: triangles order_[first, first + count)
    int right = -1;            // inner node: left child is the next node, right child here
  };
  int build(int first, int count, std::vector<BoundingBox>& boxes, std::vector<Vec3>& centres);

  std::vector<std::array<Vec3, 3>> triangles_;
  std::vector<Node> nodes_;
  std::vector<int> order_;
};

}  // namespace sheetgen
