#include "sheetgen/env/triangle_bvh.hpp"

#include <algorithm>
#include <numeric>

namespace sheetgen {

namespace {
constexpr int kLeafSize = 4;

bool meets(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}
}  // namespace

TriangleBvh::TriangleBvh(std::vector<std::array<Vec3, 3>> triangles) : triangles_(std::move(triangles)) {
  const int n = size();
  if (n == 0) return;
  std::vector<BoundingBox> boxes(n);
  std::vector<Vec3> centres(n);
  for (int i = 0; i < n; ++i) {
    for (const Vec3& p : triangles_[i]) boxes[i].extend(p);
    centres[i] = 0.5 * (boxes[i].min + boxes[i].max);
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  build(0, n, boxes, centres);
}

// Median split on the longest axis of the centres' extent: O(n log n), and
// balanced, which is all a few-thousand-triangle scene needs.
int TriangleBvh::build(int first, int count, std::vector<BoundingBox>& boxes, std::vector<Vec3>& centres) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  BoundingBox box, centre_box;
  for (int k = first; k < first + count; ++k) {
    box.extend(boxes[order_[k]]);
    centre_box.extend(centres[order_[k]]);
  }
  nodes_[id].box = box;
  if (count <= kLeafSize) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  int axis = 0;
  centre_box.size().maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                   [&](int a, int b) { return centres[a][axis] < centres[b][axis]; });
  build(first, mid - first, boxes, centres);
  const int right = build(mid, first + count - mid, boxes, centres);
  nodes_[id].right = right;
  return id;
}

bool TriangleBvh::overlapping(const BoundingBox& box, std::vector<int>& out, int cap) const {
  if (nodes_.empty()) return true;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  const size_t start = out.size();
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!meets(node.box, box)) continue;
    if (node.right < 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const int t = order_[k];
        BoundingBox tb;
        for (const Vec3& p : triangles_[t]) tb.extend(p);
        if (!meets(tb, box)) continue;
        out.push_back(t);
        if (static_cast<int>(out.size() - start) > cap) return false;
      }
      continue;
    }
    const int left = static_cast<int>(&node - nodes_.data()) + 1;
    stack[top++] = node.right;
    stack[top++] = left;
  }
  return true;
}

}  // namespace sheetgen
