// Closed-form and standard shell benchmarks (docs/fem.md "Reference
// values"). Each test prints the value it measured so docs/fem.md can quote it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem_test_models.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {
namespace {

using test::GridBuilder;

Material material(double E, double nu, double t) {
  Material m;
  m.youngs_modulus = E;
  m.poisson_ratio = nu;
  m.thickness = t;
  return m;
}

// Splits a total force over a line of nodes by the trapezoidal rule (the
// consistent load of a uniform line load on linear edges).
void line_load(ShellModel& m, const std::vector<int>& line, const Vec3& total) {
  const int n = static_cast<int>(line.size()) - 1;
  for (int k = 0; k <= n; ++k) m.add_load(line[k], total * ((k == 0 || k == n) ? 0.5 : 1.0) / n);
}

double mean_dof(const ShellResult& r, const std::vector<int>& nodes, int dof) {
  double s = 0;
  for (int i : nodes) s += r.displacements[i](dof);
  return s / nodes.size();
}

// Cantilever strip L = 100, b = 20, t = 1.6 mm, E = 73 100 MPa, nu = 0, tip
// load P = 1 N: delta = P L^3 / (3 E I) = 0.66795 mm; surface stress at
// x = 50 mm: 6 P (L - x) / (b t^2) = 5.8594 MPa.
struct Cantilever {
  ShellModel model;
  std::vector<int> tip;
  ShellResult result;
  Cantilever(int nx, int ny) {
    model.material = material(73.1e9, 0.0, 1.6e-3);
    GridBuilder g(model);
    const auto grid = g.flat(Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.02, 0), nx, ny);
    for (int j = 0; j <= ny; ++j) model.clamp(grid[0][j]);
    tip = grid[nx];
    line_load(model, tip, Vec3(0, 0, 1.0));
    result = solve_shell(model);
  }
};

TEST(ShellBenchmarks, CantileverStripTipDeflection) {
  Cantilever c(40, 8);
  const double I = 0.02 * std::pow(1.6e-3, 3) / 12.0;
  const double exact = std::pow(0.1, 3) / (3.0 * 73.1e9 * I);
  const double w = mean_dof(c.result, c.tip, kUz);
  std::printf("cantilever tip deflection %.6g mm (exact %.6g mm)\n", w * 1e3, exact * 1e3);
  EXPECT_NEAR(w, exact, 0.01 * exact);
  EXPECT_NEAR(w, 0.668e-3, 0.01 * 0.668e-3);
  // C = f^T u with 1 N spread over the tip: the load-weighted mean of u_z, which
  // differs from the plain mean only by the (nu = 0, tiny) tip warping.
  EXPECT_NEAR(c.result.compliance, 1.0 * w, 1e-4 * w);
}

TEST(ShellBenchmarks, ThickCantileverFollowsTimoshenko) {
  // L = 20, b = 10, t = 4 mm, nu = 0 (no anticlastic coupling, so the strip is
  // a beam): delta = P L^3 / (3 E I) + P L / (kappa_s G b t). Shear is 5.3 % of
  // it, which a Kirchhoff plate (DKT) misses and DKMT must catch.
  const double L = 0.02, b = 0.01, t = 0.004, E = 73.1e9, P = 1.0;
  const double bending = P * L * L * L / (3 * E * b * t * t * t / 12);
  const double shear = P * L / (5.0 / 6.0 * E / 2.0 * b * t);
  for (bool with_shear : {true, false}) {
    ShellModel m;
    m.material = material(E, 0.0, t);
    GridBuilder g(m);
    const auto grid = g.flat(Vec3(0, 0, 0), Vec3(L, 0, 0), Vec3(0, b, 0), 32, 16);
    for (int j = 0; j <= 16; ++j) m.clamp(grid[0][j]);
    line_load(m, grid[32], Vec3(0, 0, P));
    ShellSolveOptions options;
    options.element.transverse_shear = with_shear;
    const double w = mean_dof(solve_shell(m, options), grid[32], kUz);
    std::printf("thick cantilever, %s: %.6g um (Timoshenko %.6g, bending alone %.6g)\n",
                with_shear ? "DKMT" : "DKT", w * 1e6, (bending + shear) * 1e6, bending * 1e6);
    EXPECT_NEAR(w, with_shear ? bending + shear : bending, 0.005 * (bending + shear));
  }
}

TEST(ShellBenchmarks, CantileverSurfaceStressAtMidSpan) {
  // 40 cells along 100 mm: the elements of the two cells either side of
  // x = 50 mm have centroids averaging exactly x = 50 mm, and sigma_xx is
  // linear in x, so their mean is the value at x = 50 mm.
  Cantilever c(40, 8);
  double sum = 0;
  int count = 0;
  for (size_t e = 0; e < c.model.triangles.size(); ++e) {
    const auto& t = c.model.triangles[e];
    const Vec3 x = (c.model.nodes[t[0]] + c.model.nodes[t[1]] + c.model.nodes[t[2]]) / 3.0;
    if (x.x() < 0.0475 || x.x() > 0.0525) continue;
    Vector18d u;
    for (int k = 0; k < 3; ++k) u.segment<6>(6 * k) = c.result.displacements[t[k]];
    const std::array<Vec3, 3> xs = {c.model.nodes[t[0]], c.model.nodes[t[1]], c.model.nodes[t[2]]};
    const ShellStress s = shell_element_stress(xs, c.model.material, u);
    sum += std::abs(stress_to_world(shell_frame(xs), s.top)(0, 0));
    ++count;
  }
  ASSERT_EQ(count, 2 * 2 * 8);
  const double sigma = sum / count;
  std::printf("cantilever surface sigma_xx at x = 50 mm: %.6g MPa (exact 5.8594)\n", sigma * 1e-6);
  EXPECT_NEAR(sigma, 5.8594e6, 0.02 * 5.8594e6);
}

TEST(ShellBenchmarks, LBracketTipDisplacement) {
  // Leg 1 in z = 0, x in [0, 50] mm, clamped at x = 0; fold at x = 50 into
  // leg 2 in x = 50, z in [0, 30]; width 20, t = 1.6, nu = 0; 1 N along x on
  // the top edge. Reference u_x = 0.108231 mm (CalculiX S4, docs/fem.md "Reference values"; beam
  // theory gives P h^3/3EI + P h^2 a/EI + P a/EA = 0.10823 mm).
  ShellModel m;
  m.material = material(73.1e9, 0.0, 1.6e-3);
  GridBuilder g(m);
  const auto leg1 = g.flat(Vec3(0, 0, 0), Vec3(0.05, 0, 0), Vec3(0, 0.02, 0), 20, 8);
  const auto leg2 = g.flat(Vec3(0.05, 0, 0), Vec3(0, 0, 0.03), Vec3(0, 0.02, 0), 12, 8);
  for (int j = 0; j <= 8; ++j) m.clamp(leg1[0][j]);
  line_load(m, leg2[12], Vec3(1.0, 0, 0));
  const ShellResult r = solve_shell(m);
  const double ux = mean_dof(r, leg2[12], kUx);
  std::printf("L-bracket u_x %.6g mm (reference 0.108231)\n", ux * 1e3);
  EXPECT_NEAR(ux, 0.108231e-3, 0.01 * 0.108231e-3);
}

TEST(ShellBenchmarks, ClampedSquarePlateUnderPressure) {
  // w_c = 0.0012653 q a^4 / D (Timoshenko), nu = 0.3, full plate 16 x 16 cells.
  const double a = 1.0, t = 0.01, E = 1e9, nu = 0.3, q = 1.0;
  ShellModel m;
  m.material = material(E, nu, t);
  GridBuilder g(m);
  const int n = 16;
  const auto grid = g.flat(Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(0, a, 0), n, n);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      if (i == 0 || j == 0 || i == n || j == n) m.clamp(grid[i][j]);
  m.add_surface_traction(Vec3(0, 0, -q));
  const ShellResult r = solve_shell(m);
  const double D = E * t * t * t / (12 * (1 - nu * nu));
  const double exact = 0.0012653 * q * std::pow(a, 4) / D;
  const double w = -r.displacements[grid[n / 2][n / 2]](kUz);
  std::printf("clamped plate w_c / (q a^4 / D) = %.6g (exact 0.0012653)\n", w * D / (q * std::pow(a, 4)));
  EXPECT_NEAR(w, exact, 0.02 * exact);
}

TEST(ShellBenchmarks, ScordelisLoRoof) {
  // R = 25, L = 50, t = 0.25, 40 deg, E = 4.32e8, nu = 0, 90 per area down,
  // rigid diaphragms at the curved ends. Quarter model (symmetry at mid-span
  // and at the crown), faceted by flat triangles; 16 x 16 cells. Reference:
  // mid-span free-edge vertical displacement 0.3024.
  const double R = 25, half_L = 25, phi_max = 40.0 * M_PI / 180.0;
  ShellModel m;
  m.material = material(4.32e8, 0.0, 0.25);
  GridBuilder g(m, 1e-9);
  const int n = 16;
  // s: crown (phi = 0) -> free edge; t: diaphragm (y = 0) -> mid-span (y = 25).
  const auto grid = g.patch(
      [&](double s, double t) {
        const double phi = s * phi_max;
        return Vec3(R * std::sin(phi), t * half_L, R * std::cos(phi));
      },
      n, n);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      NodeSupport sp;
      sp.node = grid[i][j];
      sp.fixed.fill(false);
      if (j == 0) sp.fixed[kUx] = sp.fixed[kUz] = true;                          // diaphragm
      if (j == n) sp.fixed[kUy] = sp.fixed[kRx] = sp.fixed[kRz] = true;          // mid-span symmetry
      if (i == 0) sp.fixed[kUx] = sp.fixed[kRy] = sp.fixed[kRz] = true;          // crown symmetry
      if (std::find(sp.fixed.begin(), sp.fixed.end(), true) != sp.fixed.end()) m.supports.push_back(sp);
    }
  m.add_surface_traction(Vec3(0, 0, -90.0));
  const ShellResult r = solve_shell(m);
  const double w = -r.displacements[grid[n][n]](kUz);
  std::printf("Scordelis-Lo mid-span free-edge deflection %.6g (reference 0.3024)\n", w);
  EXPECT_NEAR(w, 0.3024, 0.03 * 0.3024);
}

// Twisted beam (MacNeal & Harder 1985): L = 12, W = 1.1, t = 0.32, 90 deg
// twist, E = 29e6, nu = 0.22, clamped root, unit tip load through a rigid tip.
double twisted_beam(const Vec3& load_direction) {
  const double L = 12, W = 1.1;
  ShellModel m;
  m.material = material(29e6, 0.22, 0.32);
  GridBuilder g(m, 1e-9);
  const int nx = 48, nw = 4;
  const auto grid = g.patch(
      [&](double s, double t) {
        const double phi = 0.5 * M_PI * s, w = (t - 0.5) * W;
        return Vec3(s * L, w * std::cos(phi), w * std::sin(phi));
      },
      nx, nw);
  for (int j = 0; j <= nw; ++j) m.clamp(grid[0][j]);
  const int master = m.add_node(Vec3(L, 0, 0));
  RigidLink tip;
  tip.master = master;
  for (int j = 0; j <= nw; ++j) tip.slaves.push_back(grid[nx][j]);
  m.rigid_links.push_back(tip);
  m.add_load(master, load_direction);
  m.load_node = master;
  const ShellResult r = solve_shell(m);
  return r.displacements[master].head<3>().dot(load_direction);
}

TEST(ShellBenchmarks, TwistedBeamLoadAlongTipWidth) {
  // At the tip the width lies along z (90 deg of twist).
  const double u = twisted_beam(Vec3(0, 0, 1));
  std::printf("twisted beam, load along tip width: %.6g (reference 5.424e-3)\n", u);
  EXPECT_NEAR(u, 5.424e-3, 0.03 * 5.424e-3);
}

TEST(ShellBenchmarks, TwistedBeamLoadAcrossTipWidth) {
  const double u = twisted_beam(Vec3(0, 1, 0));
  std::printf("twisted beam, load across tip width: %.6g (reference 1.754e-3)\n", u);
  EXPECT_NEAR(u, 1.754e-3, 0.03 * 1.754e-3);
}

}  // namespace
}  // namespace sheetgen
