// Linear buckling against closed forms (docs/fem.md "Buckling").
#include "sheetgen/fem/buckling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sheetgen/fem/fem_error.hpp"
#include "strip_models.hpp"

namespace sheetgen {
namespace {

using test::add_edge_force;
using test::strip;

double strip_ei(const test::Strip& s) {
  const Material& m = s.model.material;
  return m.youngs_modulus * s.width * std::pow(m.thickness, 3) / 12.0;
}

// Euler's column clamped at x = 0 and free at x = L under an axial force at
// the tip: P_cr = pi^2 EI / (4 L^2). nu = 0, so the strip's plate stiffness
// is the beam's EI (no anticlastic ambiguity).
TEST(Buckling, ClampedFreeStripMatchesEuler) {
  test::Strip s = strip(80, 4);
  for (int n : s.grid.front()) s.model.clamp(n);
  add_edge_force(s.model, s.grid.back(), Vec3(-1.0, 0, 0));  // 1 N: lambda is P_cr in N
  ShellSolver solver;
  const ShellResult stat = solver.solve(s.model);
  const BucklingResult b = analyse_buckling(solver, s.model, stat);
  const double euler = M_PI * M_PI * strip_ei(s) / (4 * s.length * s.length);
  ASSERT_TRUE(b.compressed);
  ASSERT_EQ(b.factors.size(), 1u);
  std::printf("clamped-free strip: lambda %.6g N, Euler %.6g N, ratio %.4f\n", b.factor(), euler, b.factor() / euler);
  EXPECT_NEAR(b.factor() / euler, 1.0, 0.02);
  // The mode bends out of plane: the tip moves along z, not in the sheet.
  const Vector6d tip = b.mode_shapes[0][s.grid.back()[2]];
  EXPECT_GT(std::abs(tip(kUz)), 0.99);
}

// Both ends clamped, the x = L end free to slide along x only:
// P_cr = 4 pi^2 EI / L^2.
TEST(Buckling, ClampedClampedStripMatchesEuler) {
  test::Strip s = strip(80, 4);
  for (int n : s.grid.front()) s.model.clamp(n);
  for (int n : s.grid.back()) {
    NodeSupport sp{n};
    sp.fixed[kUx] = false;
    s.model.supports.push_back(sp);
  }
  add_edge_force(s.model, s.grid.back(), Vec3(-1.0, 0, 0));
  ShellSolver solver;
  const ShellResult stat = solver.solve(s.model);
  const BucklingResult b = analyse_buckling(solver, s.model, stat);
  const double euler = 4 * M_PI * M_PI * strip_ei(s) / (s.length * s.length);
  std::printf("clamped-clamped strip: lambda %.6g N, Euler %.6g N, ratio %.4f\n", b.factor(), euler, b.factor() / euler);
  EXPECT_NEAR(b.factor() / euler, 1.0, 0.02);
}

// A simply supported square plate (w = 0 on every edge) compressed uniformly
// along x, the unloaded edges free to move in plane: N_cr = k pi^2 D / b^2
// with k = 4 (Timoshenko & Gere, Theory of Elastic Stability, sec. 9.2).
TEST(Buckling, SimplySupportedSquarePlateHasKFour) {
  const int n = 24;
  test::Strip s = strip(n, n, 0.33, 0.2, 0.2);
  ShellModel& m = s.model;
  std::vector<int> on_edge;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      if (i == 0 || j == 0 || i == n || j == n) {
        NodeSupport sp{s.grid[i][j]};
        sp.fixed = {i == 0, i == 0 && j == 0, true, false, false, false};  // w = 0; x = 0 edge held along x
        m.supports.push_back(sp);
      }
  const double b = s.width;
  add_edge_force(m, s.grid.back(), Vec3(-b, 0, 0));  // N = 1 N/m: lambda is N_cr in N/m
  ShellSolver solver;
  const ShellResult stat = solver.solve(m);
  const BucklingResult r = analyse_buckling(solver, m, stat);
  const Material& mat = m.material;
  const double D = mat.youngs_modulus * std::pow(mat.thickness, 3) / (12 * (1 - mat.poisson_ratio * mat.poisson_ratio));
  const double closed = 4 * M_PI * M_PI * D / (b * b);
  std::printf("SS square plate: N_cr %.6g N/m, k = 4 gives %.6g N/m, ratio %.4f\n", r.factor(), closed, r.factor() / closed);
  EXPECT_NEAR(r.factor() / closed, 1.0, 0.03);
}

// Uniform tension (nu = 0, both ends held so that the field is exactly
// uniform: the loaded end rigid, the other free in y): no element is in
// compression, so no eigen solve is made and nothing buckles.
TEST(Buckling, UniformTensionCannotBuckle) {
  test::Strip s = strip(20, 2);
  ShellModel& m = s.model;
  for (size_t j = 0; j < s.grid.front().size(); ++j) {
    NodeSupport sp{s.grid.front()[j]};
    sp.fixed = {true, j == 0, true, true, true, true};
    m.supports.push_back(sp);
  }
  const int master = m.add_node(Vec3(s.length, s.width / 2, 0));
  m.rigid_links.push_back(RigidLink{master, s.grid.back()});
  m.add_load(master, Vec3(1.0, 0, 0));
  ShellSolver solver;
  const BucklingResult b = analyse_buckling(solver, m, solver.solve(m));
  EXPECT_FALSE(b.compressed);
  EXPECT_TRUE(std::isinf(b.factor()));
  EXPECT_EQ(b.operations, 0);
}

// Tension with the end clamped: the clamp's corners leave small parasitic
// compression in the discrete field, so the eigen solve runs, but the factor
// is orders of magnitude above the same strip's compressive buckling load.
TEST(Buckling, ClampedTensionBucklesFarAboveCompression) {
  test::Strip s = strip(20, 2);
  for (int n : s.grid.front()) s.model.clamp(n);
  add_edge_force(s.model, s.grid.back(), Vec3(1.0, 0, 0));
  ShellSolver solver;
  const double tension = analyse_buckling(solver, s.model, solver.solve(s.model)).factor();
  for (auto& f : s.model.loads) f.force = -f.force;
  const double compression = analyse_buckling(solver, s.model, solver.solve(s.model)).factor();
  std::printf("clamped strip, 1 N: buckles at %.4g N in compression, %.4g N in tension\n", compression, tension);
  EXPECT_GT(tension, 1000 * compression);
}

// Doubling the load halves the factor (the eigenproblem is linear in the load).
TEST(Buckling, FactorScalesInverselyWithTheLoad) {
  test::Strip s = strip(40, 2);
  for (int n : s.grid.front()) s.model.clamp(n);
  add_edge_force(s.model, s.grid.back(), Vec3(-1.0, 0, 0.01));
  ShellSolver solver;
  const double one = analyse_buckling(solver, s.model, solver.solve(s.model)).factor();
  for (auto& f : s.model.loads) f.force *= 2.0;
  const double two = analyse_buckling(solver, s.model, solver.solve(s.model)).factor();
  EXPECT_NEAR(two * 2.0 / one, 1.0, 1e-9);
}

// One Lanczos run over both ends of the pencil answers for the load and its
// opposite: each factor equals the separate solve's to 1e-7 (both converge to
// a relative residual of 1e-9, which bounds a symmetric problem's eigenvalue
// error far below that). The strip buckles in compression at the Euler load
// and in tension only through its clamp's parasitic compression, 1000x higher.
TEST(Buckling, BothWaysEqualsTheTwoSeparateSolves) {
  test::Strip s = strip(40, 2);
  for (int n : s.grid.front()) s.model.clamp(n);
  add_edge_force(s.model, s.grid.back(), Vec3(-1.0, 0, 0.01));
  ShellSolver solver;
  const ShellResult stat = solver.solve(s.model);
  const BucklingPair pair = analyse_buckling_both_ways(solver, s.model, stat);
  const double compression = analyse_buckling(solver, s.model, stat).factor();
  for (auto& f : s.model.loads) f.force = -f.force;
  const double tension = analyse_buckling(solver, s.model, solver.solve(s.model)).factor();
  std::printf("strip both ways: %.9g / %.9g N (compression), %.9g / %.9g N (tension)\n", pair.first.factor(),
              compression, pair.second.factor(), tension);
  ASSERT_TRUE(pair.first.compressed && pair.second.compressed);
  EXPECT_NEAR(pair.first.factor() / compression, 1.0, 1e-7);
  EXPECT_NEAR(pair.second.factor() / tension, 1.0, 1e-7);
  EXPECT_GT(tension, 1000 * compression);
  ASSERT_EQ(pair.second.mode_shapes.size(), 1u);
}

TEST(Buckling, ReferenceOfAnotherModelIsRefused) {
  test::Strip s = strip(10, 2);
  for (int n : s.grid.front()) s.model.clamp(n);
  add_edge_force(s.model, s.grid.back(), Vec3(-1.0, 0, 0));
  ShellSolver solver;
  ShellResult wrong;
  wrong.displacements.resize(3);
  EXPECT_THROW(analyse_buckling(solver, s.model, wrong), FemError);
}

}  // namespace
}  // namespace sheetgen
