// The in-place assembly into the node-block pattern against the triplet
// assembly (Eigen's setFromTriplets): the same pattern and the same values to
// the last bit, on models with partial supports, a rigid load box, a
// self-rivet tie and a point mass, and through the fallback on a map that is
// not node-blocked.
#include <gtest/gtest.h>

#include <cstring>

#include "fem_test_models.hpp"
#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/shell_element.hpp"

namespace sheetgen {
namespace {

using test::GridBuilder;

// Two strips, the second tied to the first by a self-rivet link, a rigid box
// on the first's free end with a point-mass block on its master; one edge
// clamped and one node held in z only.
struct LinkedStrips {
  ShellModel model;
  int box_master = -1;
  LinkedStrips() {
    model.material.thickness = 1.6e-3;
    GridBuilder g(model);
    const auto a = g.flat(Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.02, 0), 12, 3);
    const auto b = g.flat(Vec3(0.05, 0.0, 0.004), Vec3(0.06, 0, 0), Vec3(0, 0.02, 0.01), 6, 3);
    for (int j = 0; j <= 3; ++j) model.clamp(a[0][j]);
    NodeSupport z_only;
    z_only.node = a[6][0];
    z_only.fixed = {false, false, true, false, false, false};
    model.supports.push_back(z_only);
    RigidLink rivet{a[8][1], {b[2][1]}};
    model.rigid_links.push_back(rivet);
    RigidLink box;
    box_master = box.master = model.add_node(Vec3(0.095, 0.01, 0.01));
    for (int i = 11; i <= 12; ++i)
      for (int j = 0; j <= 3; ++j) box.slaves.push_back(a[i][j]);
    model.rigid_links.push_back(box);
  }
  Matrix18d element(int e) const {
    const auto& t = model.triangles[e];
    return shell_element_stiffness({model.nodes[t[0]], model.nodes[t[1]], model.nodes[t[2]]}, model.material, {});
  }
};

// Same rows, columns and value bits.
void expect_identical(const SparseMatrix& a, const SparseMatrix& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  ASSERT_TRUE(a.isCompressed() && b.isCompressed());
  EXPECT_EQ(0, std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * (a.cols() + 1)));
  EXPECT_EQ(0, std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * a.nonZeros()));
  EXPECT_EQ(0, std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * a.nonZeros()));
}

TEST(NodeBlockPattern, InPlaceAssemblyEqualsTheTripletsBitForBit) {
  const LinkedStrips s;
  const DofMap map = build_dof_map(s.model);
  auto element = [&](int e) { return s.element(e); };
  Matrix6d block = Matrix6d::Identity() * 2.5;
  block(0, 4) = block(4, 0) = 0.3;
  const std::vector<NodalBlock> blocks{{s.box_master, block}};
  const SparseMatrix fast = assemble_elements(s.model, map, element, blocks);
  const SparseMatrix reference = assemble_elements_by_triplets(s.model, map, element, blocks);
  EXPECT_GT(fast.nonZeros(), 1000);
  expect_identical(fast, reference);
  // And again on the same thread with another model: the workspace resized, not stale.
  ShellModel small;
  GridBuilder g(small);
  g.flat(Vec3(0, 0, 0), Vec3(0.02, 0, 0), Vec3(0, 0.02, 0), 2, 2);
  small.material.thickness = 1.6e-3;
  small.clamp(0);
  const DofMap small_map = build_dof_map(small);
  auto small_element = [&](int e) {
    const auto& t = small.triangles[e];
    return shell_element_stiffness({small.nodes[t[0]], small.nodes[t[1]], small.nodes[t[2]]}, small.material, {});
  };
  expect_identical(assemble_elements(small, small_map, small_element),
                   assemble_elements_by_triplets(small, small_map, small_element));
}

TEST(NodeBlockPattern, AMapThatIsNotNodeBlockedFallsBackToTheTriplets) {
  // Node 1's x follows node 0's x and nothing else: an element on node 1
  // names one DOF of node 0's range, so whole node blocks would hold entries
  // the triplets do not.
  const LinkedStrips s;
  DofMap map = build_dof_map(s.model);
  const int n0 = s.model.triangles[40][0], n1 = s.model.triangles[40][1];
  ASSERT_EQ(map.start[6 * n0 + 1] - map.start[6 * n0], 1);
  const int x0 = map.index[map.start[6 * n0]];
  const int p = map.start[6 * n1];
  ASSERT_EQ(map.start[6 * n1 + 1] - p, 1);
  map.index[p] = x0;  // node 1's own x is left unused (a zero column)
  auto element = [&](int e) { return s.element(e); };
  const SparseMatrix fast = assemble_elements(s.model, map, element);
  const SparseMatrix reference = assemble_elements_by_triplets(s.model, map, element);
  expect_identical(fast, reference);
}

}  // namespace
}  // namespace sheetgen
