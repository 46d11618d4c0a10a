// Several load cases on one factorisation (docs/fem.md "Load cases").
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "fem_brackets.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/shell_element.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {
namespace {

// Six cases on the three-tab bracket: +-x, +-y, +-z forces with moments on
// its load node, as an inertia envelope puts them.
ShellModel six_case_bracket() {
  ShellModel m = test::three_tab_bracket_model(4e-3);
  const int node = m.load_node;
  const Vec3 dirs[6] = {Vec3(90, 0, 0), Vec3(-15, 0, 0), Vec3(0, 30, 0), Vec3(0, -30, 0), Vec3(0, 0, -60), Vec3(0, 0, 30)};
  const char* names[6] = {"forward", "rearward", "left", "right", "down", "up"};
  for (int c = 0; c < 6; ++c) {
    ShellLoadCase lc;
    lc.name = names[c];
    lc.loads.push_back(NodalLoad{node, dirs[c], Vec3(0.1 * c, -0.2, 0.05)});
    m.load_cases.push_back(lc);
  }
  return m;
}

TEST(LoadCases, SixCasesOnOneFactorisationEqualSixSolves) {
  const ShellModel m = six_case_bracket();
  ShellSolver together;
  const std::vector<ShellResult> all = together.solve_cases(m);
  ASSERT_EQ(all.size(), 6u);
  EXPECT_EQ(together.symbolic_analyses(), 1);
  for (int c = 0; c < 6; ++c) {
    ShellModel one = m;
    one.load_cases.clear();
    one.loads = m.load_cases[c].loads;
    const ShellResult alone = solve_shell(one);
    EXPECT_EQ(all[c].case_name, m.load_cases[c].name);
    EXPECT_NEAR(all[c].compliance / alone.compliance, 1.0, 1e-10);
    double worst = 0, scale = 0;
    for (size_t i = 0; i < alone.displacements.size(); ++i) {
      worst = std::max(worst, (all[c].displacements[i] - alone.displacements[i]).cwiseAbs().maxCoeff());
      scale = std::max(scale, alone.displacements[i].cwiseAbs().maxCoeff());
    }
    EXPECT_LE(worst, 1e-10 * scale) << "case " << c;
    EXPECT_NEAR(all[c].max_von_mises / alone.max_von_mises, 1.0, 1e-10);
    EXPECT_NEAR(all[c].margin_of_safety, alone.margin_of_safety, 1e-10 * std::abs(alone.margin_of_safety));
  }
}

// The cases share each element's stress operator and the stress rule's
// singular points: every case's element stresses are, bit for bit, those of
// its own displacements, the excluded elements and corners those of a
// one-case solve, and the membrane stress without the bending operator is
// the full stress's membrane part.
TEST(LoadCases, SharedStressOperatorsGiveEachCasesOwnStresses) {
  const ShellModel m = six_case_bracket();
  ShellSolver solver;
  const std::vector<ShellResult> all = solver.solve_cases(m);
  ShellModel one = m;
  one.load_cases.clear();
  one.loads = m.load_cases[0].loads;
  const ShellResult alone = solve_shell(one);
  int compared = 0;
  for (const ShellResult& res : all) {
    EXPECT_EQ(res.stress_excluded, alone.stress_excluded);
    EXPECT_EQ(res.reentrant_corners, alone.reentrant_corners);
    for (size_t e = 0; e < m.triangles.size(); ++e) {
      const auto& t = m.triangles[e];
      const std::array<Vec3, 3> nodes = {m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]};
      Vector18d ue;
      for (int k = 0; k < 3; ++k) ue.segment<6>(6 * k) = res.displacements[t[k]];
      const ShellStress own = shell_element_stress(nodes, m.material, ue);
      ASSERT_EQ(res.von_mises_top[e], own.von_mises_top) << res.case_name << ", element " << e;
      ASSERT_EQ(res.von_mises_bottom[e], own.von_mises_bottom) << res.case_name << ", element " << e;
      const Eigen::Vector3d membrane = membrane_stress(shell_stress_operator(nodes, m.material, {}, false), ue);
      ASSERT_EQ(membrane, own.membrane) << res.case_name << ", element " << e;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6 * static_cast<int>(m.triangles.size()));
  EXPECT_GT(std::count(alone.stress_excluded.begin(), alone.stress_excluded.end(), true), 0);
}

// deflection_along_load is the load node's translation along the resultant force.
TEST(LoadCases, DeflectionAlongTheLoad) {
  const ShellModel m = six_case_bracket();
  const std::vector<ShellResult> all = solve_shell_cases(m);
  for (size_t c = 0; c < all.size(); ++c) {
    const Vec3 u = all[c].displacements[m.load_node].head<3>();
    EXPECT_NEAR(all[c].deflection_along_load, u.dot(m.load_cases[c].loads[0].force.normalized()), 1e-15);
    EXPECT_LE(std::abs(all[c].deflection_along_load), all[c].load_deflection * (1 + 1e-12));
  }
}

TEST(LoadCases, ACaseWithoutLoadIsNamed) {
  ShellModel m = six_case_bracket();
  m.load_cases[3].loads[0].force.setZero();
  m.load_cases[3].loads[0].moment.setZero();
  try {
    solve_shell_cases(m);
    ADD_FAILURE() << "an unloaded case was solved";
  } catch (const FemError& e) {
    EXPECT_NE(e.field().find("'right'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sheetgen
