// The model layer: rigid links (load box, self-rivets), error reporting, the
// stress rule, mesh convergence and the cached factorisation.
#include "sheetgen/fem/shell_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "fem_test_models.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/plate_mesher.hpp"

namespace sheetgen {
namespace {

using test::GridBuilder;

Material aluminium_nu0() {
  Material m;
  m.youngs_modulus = 73.1e9;
  m.poisson_ratio = 0.0;
  m.thickness = 1.6e-3;
  return m;
}

// Strip 100 x 20 mm clamped at x = 0, 40 x 8 cells.
struct Strip {
  ShellModel model;
  std::vector<std::vector<int>> grid;
  Strip() {
    model.material = aluminium_nu0();
    GridBuilder g(model);
    grid = g.flat(Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.02, 0), 40, 8);
    for (int j = 0; j <= 8; ++j) model.clamp(grid[0][j]);
  }
};

TEST(ShellModel, RigidLoadBoxMovesItsSlavesRigidly) {
  // A rigid box bonded on the last 10 mm of the strip, master at the box
  // centroid 5 mm above the sheet, loaded by a force and a moment.
  Strip s;
  ShellModel& m = s.model;
  const Vec3 centroid(0.095, 0.01, 0.005);
  RigidLink box;
  box.master = m.add_node(centroid);
  for (int i = 36; i <= 40; ++i)
    for (int j = 0; j <= 8; ++j) box.slaves.push_back(s.grid[i][j]);
  m.rigid_links.push_back(box);
  const Vec3 F(3.0, -2.0, 1.0), M(0.01, 0.02, -0.015);
  m.add_load(box.master, F, M);
  m.load_node = box.master;
  const ShellResult r = solve_shell(m);
  const Vector6d um = r.displacements[box.master];
  const Vec3 tm = um.head<3>(), rm = um.tail<3>();
  for (int sl : box.slaves) {
    const Vector6d us = r.displacements[sl];
    const Vec3 expect = tm + rm.cross(m.nodes[sl] - centroid);
    EXPECT_LT((us.head<3>() - expect).norm(), 1e-12 * tm.norm());
    EXPECT_LT((us.tail<3>() - rm).norm(), 1e-12 * rm.norm());
  }
  // Elements inside the box move rigidly: no stress (to round-off).
  double inside_max = 0, overall = 0;
  for (size_t e = 0; e < m.triangles.size(); ++e) {
    const double v = std::max(r.von_mises_top[e], r.von_mises_bottom[e]);
    overall = std::max(overall, v);
    bool all_slaves = true;
    for (int k : m.triangles[e]) all_slaves = all_slaves && m.nodes[k].x() >= 0.09 - 1e-12;
    if (all_slaves) inside_max = std::max(inside_max, v);
  }
  EXPECT_LT(inside_max, 1e-9 * overall);
  // Compliance is the work of the force and the moment at the master.
  EXPECT_NEAR(r.compliance, F.dot(tm) + M.dot(rm), 1e-9 * std::abs(r.compliance));
  EXPECT_NEAR(r.load_deflection, tm.norm(), 1e-15);
  EXPECT_EQ(r.load_node, box.master);
}

TEST(ShellModel, MomentOnBoxMasterBendsTheStripLikeABeam) {
  // Pure moment M_y = 0.01 N m on the box over x in [90, 100] mm: the free
  // length a = 90 mm is in pure bending, rotation M a / EI, deflection M a^2 / 2EI.
  Strip s;
  ShellModel& m = s.model;
  RigidLink box;
  box.master = m.add_node(Vec3(0.095, 0.01, 0.01));
  for (int i = 36; i <= 40; ++i)
    for (int j = 0; j <= 8; ++j) box.slaves.push_back(s.grid[i][j]);
  m.rigid_links.push_back(box);
  const double M = 0.01, a = 0.09, EI = 73.1e9 * 0.02 * std::pow(1.6e-3, 3) / 12;
  m.add_load(box.master, Vec3::Zero(), Vec3(0, M, 0));
  const ShellResult r = solve_shell(m);
  const double rot = r.displacements[box.master](kRy);
  const double w = r.displacements[s.grid[36][4]](kUz);
  std::printf("moment on box: rotation %.6g rad (beam %.6g), w(a) %.6g m (beam %.6g)\n", rot, M * a / EI, w,
              -M * a * a / (2 * EI));
  EXPECT_NEAR(rot, M * a / EI, 0.01 * M * a / EI);
  EXPECT_NEAR(w, -M * a * a / (2 * EI), 0.01 * M * a * a / (2 * EI));
}

TEST(ShellModel, SelfRivetTieOfCoincidentNodesEqualsAMergedMesh) {
  // Two strips meeting at x = 50 mm with duplicated nodes, tied node by node
  // with rigid links of zero length, must behave exactly like one strip.
  ShellModel tied;
  tied.material = aluminium_nu0();
  GridBuilder g1(tied), g2(tied);  // separate builders: no merging across x = 50 mm
  const auto a = g1.flat(Vec3(0, 0, 0), Vec3(0.05, 0, 0), Vec3(0, 0.02, 0), 20, 8);
  const auto b = g2.flat(Vec3(0.05, 0, 0), Vec3(0.05, 0, 0), Vec3(0, 0.02, 0), 20, 8);
  for (int j = 0; j <= 8; ++j) tied.clamp(a[0][j]);
  for (int j = 0; j <= 8; ++j) tied.rigid_links.push_back(RigidLink{a[20][j], {b[0][j]}});
  for (int j = 0; j <= 8; ++j) tied.add_load(b[20][j], Vec3(0, 0, 1.0 / 9));

  Strip merged;
  for (int j = 0; j <= 8; ++j) merged.model.add_load(merged.grid[40][j], Vec3(0, 0, 1.0 / 9));
  const ShellResult rt = solve_shell(tied), rm = solve_shell(merged.model);
  EXPECT_NEAR(rt.compliance, rm.compliance, 1e-9 * rm.compliance);

  // Without the ties the outer strip is connected to nothing.
  tied.rigid_links.clear();
  try {
    solve_shell(tied);
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("connected to no support"), std::string::npos) << e.what();
  }
}

TEST(ShellModel, BadInputThrowsNamingTheCause) {
  auto expect_error = [](const ShellModel& m, const std::string& needle) {
    try {
      solve_shell(m);
      FAIL() << "expected FemError containing '" << needle << "'";
    } catch (const FemError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  Strip s;
  s.model.add_load(s.grid[40][4], Vec3(0, 0, 1));
  {
    ShellModel m = s.model;
    m.supports.clear();
    expect_error(m, "no supported node");
  }
  {
    ShellModel m = s.model;
    m.material.thickness = 0;
    expect_error(m, "material.thickness");
    m.material.thickness = -1e-3;
    expect_error(m, "material.thickness");
  }
  {
    ShellModel m = s.model;
    m.nodes[5].y() = std::nan("");
    expect_error(m, "not finite");
  }
  {
    ShellModel m = s.model;
    m.loads[0].force.x() = std::numeric_limits<double>::infinity();
    expect_error(m, "not finite");
  }
  for (ShellSolverBackend backend : {ShellSolverBackend::kCholmodSupernodal, ShellSolverBackend::kEigenSimplicialLdlt}) {
    // Pinned (translations only) along one line: free rotation about that
    // line's axis is a mechanism the factorisation must detect.
    ShellModel m = s.model;
    for (NodeSupport& sp : m.supports) sp.fixed = {true, true, true, false, false, false};
    ShellSolveOptions opt;
    opt.backend = backend;
    try {
      solve_shell(m, opt);
      FAIL() << "expected a singular-stiffness FemError";
    } catch (const FemError& e) {
      EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
    }
  }
  {
    ShellModel m = s.model;
    m.rigid_links.push_back(RigidLink{s.grid[40][0], {s.grid[0][0]}});  // slave is clamped
    expect_error(m, "also has a support");
  }
}

TEST(ShellModel, StressRuleAndMarginOfSafety) {
  // Cantilever, 1 N at the tip: the rule excludes centroids within 2 t + h of
  // the clamp and of nothing else, so the maximum sits just outside that band
  // at sigma = 6 P (L - x) / (b t^2).
  Strip s;
  for (int j = 0; j <= 8; ++j) s.model.add_load(s.grid[40][j], Vec3(0, 0, (j == 0 || j == 8 ? 0.5 : 1.0) / 8));
  const ShellResult r = solve_shell(s.model);
  const double t = 1.6e-3, h_node = std::hypot(2.5e-3, 2.5e-3);  // longest edge at a clamped node (diagonal)
  for (size_t e = 0; e < s.model.triangles.size(); ++e) {
    const auto& tr = s.model.triangles[e];
    const double cx = (s.model.nodes[tr[0]].x() + s.model.nodes[tr[1]].x() + s.model.nodes[tr[2]].x()) / 3;
    if (cx < 2 * t + 2.5e-3 - 1e-9) {
      EXPECT_TRUE(r.stress_excluded[e]) << "element at x = " << cx;
    }
    if (cx > 2 * t + h_node + 1e-9) {
      EXPECT_FALSE(r.stress_excluded[e]) << "element at x = " << cx;
    }
  }
  const auto& tr = s.model.triangles[r.max_von_mises_element];
  const double cx = (s.model.nodes[tr[0]].x() + s.model.nodes[tr[1]].x() + s.model.nodes[tr[2]].x()) / 3;
  const double beam = 6 * 1.0 * (0.1 - cx) / (0.02 * t * t);
  EXPECT_NEAR(r.max_von_mises, beam, 0.02 * beam);
  EXPECT_FALSE(r.stress_rule_fell_back);
  EXPECT_NEAR(r.margin_of_safety, 345e6 / (1.5 * r.max_von_mises) - 1, 1e-12);
}

// Two plates through the plate mesher at element size h: the first clamped
// along its edge 3 -> 0, 1 N along x spread over the second's edge 1 -> 2.
ShellModel clamped_pair(const std::vector<Vec3>& clamped, const std::vector<Vec3>& loaded, double h, bool graded = true) {
  PlateMeshOptions opt;
  opt.element_size = h;
  opt.grade_fold_ends = graded;
  const PlateMesh pm = mesh_plates({clamped, loaded}, {}, opt);
  ShellModel m;
  m.material = aluminium_nu0();
  m.nodes = pm.mesh.vertices;
  m.triangles = pm.mesh.triangles;
  for (int n : nodes_on_segment(pm.mesh, clamped[0], clamped[3])) m.clamp(n);
  const std::vector<int> top = nodes_on_segment(pm.mesh, loaded[1], loaded[2]);
  for (size_t k = 0; k < top.size(); ++k)
    m.add_load(top[k], Vec3((k == 0 || k + 1 == top.size() ? 0.5 : 1.0) / (top.size() - 1), 0, 0));
  return m;
}

// L-bracket of docs/fem.md "Reference values" through the plate mesher at element size h.
ShellResult mesh_l_bracket(double h, ShellSolver& solver, ShellModel* out = nullptr) {
  const std::vector<Vec3> leg1 = {Vec3(0, 0, 0), Vec3(0.05, 0, 0), Vec3(0.05, 0.02, 0), Vec3(0, 0.02, 0)};
  const std::vector<Vec3> leg2 = {Vec3(0.05, 0, 0), Vec3(0.05, 0, 0.03), Vec3(0.05, 0.02, 0.03), Vec3(0.05, 0.02, 0)};
  const ShellModel m = clamped_pair(leg1, leg2, h);
  if (out) *out = m;
  return solver.solve(m);
}

TEST(ShellModel, LBracketConvergesUnderRefinement) {
  // Compliance = load-weighted u_x of the top edge (1 N); three halvings of h.
  ShellSolver solver;
  std::vector<double> c, smax;
  for (double h : {4e-3, 2e-3, 1e-3}) {
    const ShellResult r = mesh_l_bracket(h, solver);
    EXPECT_TRUE(r.reentrant_corners.empty());  // the fold spans the whole edge: 90 + 90 deg at its ends
    c.push_back(r.compliance);
    smax.push_back(r.max_von_mises);
    std::printf("L-bracket h = %.1f mm: u_x = %.6g mm, max von Mises (rule) = %.4g MPa, %d dofs\n", h * 1e3,
                r.compliance * 1e3, r.max_von_mises * 1e-6, r.reduced_dofs);
  }
  const bool monotone = (c[1] - c[0]) * (c[2] - c[1]) >= 0;
  const double spread = (*std::max_element(c.begin(), c.end()) - *std::min_element(c.begin(), c.end())) / c[2];
  EXPECT_TRUE(monotone || spread < 0.01) << "spread " << spread;
  EXPECT_NEAR(c[2], 0.108231e-3, 0.01 * 0.108231e-3);
  // The rule's maximum converges: the last halving changes it by < 3 %.
  EXPECT_LT(std::abs(smax[2] - smax[1]), 0.03 * smax[2]);
}

// A T: a 20 mm leg folded up from the middle of a 40 mm base edge, so the fold
// ends inside its parent's edge at two re-entrant corners (90 + 180 deg).
// Base clamped along x = 0, 1 N along x on the leg's top edge.
ShellResult mesh_t_bracket(double h, const ShellSolveOptions& options, ShellModel* out = nullptr, bool graded = false) {
  const std::vector<Vec3> base = {Vec3(0, 0, 0), Vec3(0.05, 0, 0), Vec3(0.05, 0.04, 0), Vec3(0, 0.04, 0)};
  const std::vector<Vec3> leg = {Vec3(0.05, 0.01, 0), Vec3(0.05, 0.01, 0.03), Vec3(0.05, 0.03, 0.03),
                                 Vec3(0.05, 0.03, 0)};
  const ShellModel m = clamped_pair(base, leg, h, graded);
  if (out) *out = m;
  return solve_shell(m, options);
}

TEST(ShellModel, FoldEndsInsideAnEdgeAreSingularPointsOfTheStressRule) {
  // On uniform meshes (the rule's own behaviour; graded meshes below).
  ShellSolveOptions without;
  without.reentrant_corner_angle = 4 * M_PI;  // no node's angles add up to this: the rule before the change
  std::vector<double> smax, sraw;
  for (double h : {4e-3, 2e-3, 1e-3}) {
    ShellModel m;
    const ShellResult r = mesh_t_bracket(h, {}, &m);
    const ShellResult w = mesh_t_bracket(h, without);
    // Exactly the two ends of the fold; the leg's top corners (90 deg) and the
    // base's corners are not re-entrant.
    ASSERT_EQ(r.reentrant_corners.size(), 2u);
    for (int n : r.reentrant_corners) {
      EXPECT_NEAR(m.nodes[n].x(), 0.05, 1e-12);
      EXPECT_NEAR(m.nodes[n].z(), 0.0, 1e-12);
      EXPECT_TRUE(std::abs(m.nodes[n].y() - 0.01) < 1e-12 || std::abs(m.nodes[n].y() - 0.03) < 1e-12);
    }
    EXPECT_TRUE(w.reentrant_corners.empty());
    smax.push_back(r.max_von_mises);
    sraw.push_back(w.max_von_mises);
    std::printf("T-bracket h = %.1f mm: max von Mises with fold ends excluded %.4g MPa, without %.4g MPa\n",
                h * 1e3, r.max_von_mises * 1e-6, w.max_von_mises * 1e-6);
  }
  // Without the corners the maximum sits at a fold end and grows by ~20 % with
  // every halving (3.95, 4.81, 5.67 MPa). With them it converges: the kept
  // band reaches towards the corners as 2 t + h shrinks to 2 t, so it still
  // rises, but by less with every halving (3.15, 3.29, 3.40 MPa: +4.6 %, +3.1 %).
  EXPECT_GT(sraw[2], 1.10 * sraw[1]);
  EXPECT_GT(sraw[1], 1.10 * sraw[0]);
  EXPECT_LT(smax[2] - smax[1], smax[1] - smax[0]);
  EXPECT_LT(std::abs(smax[2] - smax[1]), 0.04 * smax[2]);
  // Statics: the leg's root carries M = 1 N x 30 mm over b = 20 mm, so its
  // surface stress is 6 M / (b t^2) = 3.52 MPa; the kept maximum may not
  // exceed what the root sees a few millimetres in from the corners by much.
  const double t = 1.6e-3, beam_root = 6 * 1.0 * 0.03 / (0.02 * t * t);
  EXPECT_LT(smax[2], 1.5 * beam_root);
  EXPECT_GT(smax[2], 0.5 * beam_root);
}

TEST(ShellModel, GradedFoldEndsConvergeAndKeepTheStressRuleSteady) {
  // The T-bracket with the mesher's default grading at the fold ends and the
  // stress rule's clearance at re-entrant corners set to a bend radius of
  // 4 t (as analyse_part() does; docs/fem.md "Graded fold ends").
  const double t = 1.6e-3;
  ShellSolveOptions rule;
  rule.reentrant_corner_clearance = 4 * t;
  // Reference: graded at h = 0.5 mm.
  const double reference = mesh_t_bracket(0.5e-3, rule, nullptr, true).compliance;
  std::vector<double> graded_stress;
  for (double h : {4e-3, 2e-3, 1e-3}) {
    const ShellResult g = mesh_t_bracket(h, rule, nullptr, true);
    const ShellResult u = mesh_t_bracket(h, rule, nullptr, false);
    std::printf("T-bracket h = %.1f mm: compliance graded %+.3f %%, uniform %+.3f %% from graded h = 0.5 mm (%.6g J); "
                "max von Mises graded %.4g MPa, uniform %.4g MPa\n",
                h * 1e3, 100 * (g.compliance / reference - 1), 100 * (u.compliance / reference - 1), reference,
                g.max_von_mises * 1e-6, u.max_von_mises * 1e-6);
    // Graded is nearer the converged compliance than uniform at every h.
    EXPECT_LT(std::abs(g.compliance / reference - 1), std::abs(u.compliance / reference - 1));
    graded_stress.push_back(g.max_von_mises);
  }
  // With the clearance the kept maximum no longer follows the corner's
  // element size: within 3 % over h = 4, 2, 1 mm, and near the root's beam
  // stress 6 M / (b t^2) = 3.52 MPa.
  const auto [lo, hi] = std::minmax_element(graded_stress.begin(), graded_stress.end());
  EXPECT_LT(*hi / *lo - 1, 0.03);
  const double beam_root = 6 * 1.0 * 0.03 / (0.02 * t * t);
  EXPECT_GT(*lo, 0.7 * beam_root);
  EXPECT_LT(*hi, 1.3 * beam_root);
}

TEST(ShellSolver, ReusesTheSymbolicFactorisationWhileThePatternRepeats) {
  ShellSolver solver;
  ShellModel m;
  const ShellResult a = mesh_l_bracket(3e-3, solver, &m);
  EXPECT_FALSE(a.pattern_reused);
  // Same mesh, new load and thickness: same pattern, numeric factorisation only.
  m.loads[0].force *= 2;
  m.material.thickness = 2.0e-3;
  const ShellResult b = solver.solve(m);
  EXPECT_TRUE(b.pattern_reused);
  EXPECT_EQ(solver.symbolic_analyses(), 1);
  // A different mesh: a new analysis.
  const ShellResult c = mesh_l_bracket(2.5e-3, solver);
  EXPECT_FALSE(c.pattern_reused);
  EXPECT_EQ(solver.symbolic_analyses(), 2);
  // Both backends agree (b used the default, Eigen LDL^T).
  ShellSolveOptions cholmod;
  cholmod.backend = ShellSolverBackend::kCholmodSupernodal;
  const ShellResult d = solve_shell(m, cholmod);
  EXPECT_NEAR(d.compliance, b.compliance, 1e-9 * b.compliance);
}

// The static cases, buckling and vibration of one part prepare the solver with
// the same model in turn; the solver then keeps its DOF map, K and factor. Any
// change to what K is built from must give what a fresh solver gives, to the
// last bit, and the same model again must assemble nothing.
TEST(ShellSolver, KeepsItsFactorExactlyWhileTheStiffnessInputsRepeat) {
  ShellSolver solver;
  ShellModel m;
  const ShellResult first = mesh_l_bracket(3e-3, solver, &m);
  EXPECT_GT(first.assemble_seconds, 0.0);
  // The same model: nothing assembled, nothing factored, the same answer.
  m.loads[0].force *= 3;  // loads are not stiffness inputs
  const ShellResult again = solver.solve(m);
  EXPECT_EQ(again.factor_seconds, 0.0);
  EXPECT_TRUE(again.pattern_reused);
  EXPECT_EQ(again.compliance, solve_shell(m).compliance);
  // Each change below keeps the mesh's pattern, so only the inputs tell it apart.
  std::vector<std::pair<const char*, std::function<void(ShellModel&)>>> changes = {
      {"a node moved", [](ShellModel& x) { x.nodes[x.triangles[7][1]].z() += 2e-4; }},
      {"Poisson's ratio", [](ShellModel& x) { x.material.poisson_ratio = 0.3; }},
      {"Young's modulus", [](ShellModel& x) { x.material.youngs_modulus *= 0.5; }},
      {"a support released in one DOF", [](ShellModel& x) { x.supports.back().fixed[kRz] = false; }},
  };
  for (auto& [what, change] : changes) {
    change(m);
    const ShellResult kept = solver.solve(m);
    EXPECT_GT(kept.factor_seconds, 0.0) << what;
    EXPECT_EQ(kept.compliance, solve_shell(m).compliance) << what;
  }
  ShellSolveOptions kirchhoff;
  kirchhoff.element.transverse_shear = false;
  EXPECT_EQ(solver.solve(m, kirchhoff).compliance, solve_shell(m, kirchhoff).compliance);
}

}  // namespace
}  // namespace sheetgen
