// The CalculiX deck beyond one static case: a static step per load case, the
// *BUCKLE and *FREQUENCY steps, rigid masses as MASS elements in a rigid body,
// and the .dat readers (ccx_export.hpp, docs/fem.md "CalculiX export").
// Tests named "...Calculix" run ccx (the full tier); ccx is a required tool of
// this project (docs/platform.md): if it is missing they FAIL, never skip.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "fem_brackets.hpp"
#include "fem_test_models.hpp"
#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "../common/test_files.hpp"

namespace sheetgen {
namespace {

using testing::ccx_path;
using testing::temp_dir;

// A flat strip along x, clamped at x = 0, of elastic length L, width b and
// thickness t, and a rigid end plate: one more cell row beyond x = L all in
// one rigid link, whose element-free master at (L, b/2, 0) carries the loads
// and masses. The end plate is a row of cells, not the line x = L: ccx builds
// a rigid body from the translations of its nodes (a shell node's rotations
// do not enter), so nodes on one line leave the rotation about that line
// free, and the slope a rigid mass must follow would be lost. nu = 0 makes
// the plate strip a beam: EI = E b t^3 / 12.
struct Strip {
  ShellModel model;
  int tip = -1;  // the end plate's master node
  double length = 0.1, width = 0.01, thickness = 1e-3;
  double youngs_modulus = 70e9;

  double bending_stiffness() const { return youngs_modulus * width * std::pow(thickness, 3) / 12; }  // N m^2
  double sheet_mass() const { return model.material.density * length * width * thickness; }       // kg, elastic part
};

Strip cantilever_strip(int nx = 20, int ny = 2) {
  Strip s;
  ShellModel& m = s.model;
  m.material.youngs_modulus = s.youngs_modulus;
  m.material.poisson_ratio = 0;
  m.material.thickness = s.thickness;
  m.material.density = 2780;
  test::GridBuilder g(m);
  const double cell = s.length / nx;
  const auto grid = g.flat(Vec3(0, 0, 0), Vec3(s.length + cell, 0, 0), Vec3(0, s.width, 0), nx + 1, ny);
  for (int j = 0; j <= ny; ++j) m.clamp(grid[0][j]);
  RigidLink end;
  end.master = m.add_node(Vec3(s.length, 0.5 * s.width, 0));
  for (int i = nx; i <= nx + 1; ++i)
    for (int j = 0; j <= ny; ++j) end.slaves.push_back(grid[i][j]);
  m.rigid_links.push_back(end);
  s.tip = end.master;
  m.load_node = end.master;
  return s;
}

// A uniform box (sides a, m kg): its inertia about its centre, kg m^2.
Eigen::Matrix3d box_inertia(double mass, const Vec3& a) {
  return Eigen::Vector3d(mass * (a.y() * a.y() + a.z() * a.z()) / 12, mass * (a.x() * a.x() + a.z() * a.z()) / 12,
                         mass * (a.x() * a.x() + a.y() * a.y()) / 12)
      .asDiagonal();
}

// ---------------------------------------------------------------- deck, no ccx

// m, c and J of the points must be the body's exactly, whatever its
// orientation: J = sum m_i (|r_i|^2 I - r_i r_i^T) about the centre.
TEST(CcxEnvelope, LumpedMassKeepsMassCentreAndInertia) {
  const Vec3 node(0.1, -0.2, 0.3), offset(0.01, 0.02, -0.03);
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(0.3, Vec3::UnitZ())).toRotationMatrix();
  auto check = [&](const Eigen::Matrix3d& J, size_t expected_points) {
    const PointMass body{0, 2.5, offset, J};
    const std::vector<CcxLumpedMass> pts = lumped_rigid_mass(body, node);
    EXPECT_EQ(pts.size(), expected_points);
    double mass = 0;
    Vec3 first = Vec3::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (const CcxLumpedMass& p : pts) {
      const Vec3 r = p.position - (node + offset);
      mass += p.mass;
      first += p.mass * r;
      second += p.mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
      EXPECT_GT(p.mass, 0);
    }
    EXPECT_NEAR(mass, 2.5, 1e-14);
    EXPECT_LT(first.norm(), 1e-15);
    EXPECT_LT((second - J).norm(), 1e-13 * std::max(J.norm(), 1e-3)) << second << "\n\n" << J;
  };
  check(R * box_inertia(2.5, Vec3(0.04, 0.03, 0.02)) * R.transpose(), 6);  // a solid box, turned
  check(R * box_inertia(2.5, Vec3(0.04, 0.03, 0)) * R.transpose(), 5);     // a plate: no extent across it
  check(R * box_inertia(2.5, Vec3(0.04, 0, 0)) * R.transpose(), 3);        // a rod
  check(Eigen::Matrix3d::Zero(), 1);                                       // a point
  // J1 > J2 + J3 belongs to no body.
  const PointMass bad{0, 1.0, Vec3::Zero(), Eigen::Vector3d(3, 1, 1).asDiagonal()};
  EXPECT_THROW(lumped_rigid_mass(bad, node), FemError);
}

// Eigenvalue steps first, then one static step per case; supports in the
// model section; OP=NEW from the second step on; masses tied to the box's
// REF NODE by a *RIGID BODY of their own.
TEST(CcxEnvelope, DeckHasTheEigenStepsThenOneStaticStepPerCase) {
  ShellModel m = test::three_tab_bracket_model(5e-3);
  const int box = m.load_node;
  m.load_cases = {{"down", {{box, Vec3(0, 0, -100), Vec3::Zero()}}}, {"side", {{box, Vec3(0, 50, 0), Vec3::Zero()}}}};
  m.point_masses = {PointMass{box, 0.5, Vec3(0, 0, 0.005), box_inertia(0.5, Vec3(0.03, 0.02, 0.03))}};
  CcxExportOptions o;
  o.buckle_case = 1;
  o.buckling_factors = 2;
  o.frequency_modes = 4;
  std::ostringstream deck;
  const CcxDeckMap map = write_ccx_deck(m, deck, o);
  const std::string text = deck.str();
  const auto at = [&text](const std::string& key, size_t from = 0) { return text.find(key, from); };
  const size_t first_step = at("*STEP");
  EXPECT_LT(at("*BOUNDARY"), first_step);
  EXPECT_LT(at("*DENSITY\n2780\n"), first_step);
  EXPECT_LT(first_step, at("*BUCKLE\n2\n*CLOAD\n"));                        // the first step: no OP=NEW
  EXPECT_LT(at("*BUCKLE"), at("*FREQUENCY\n4\n"));
  const size_t down = at("** Load case 1 'down'"), side = at("** Load case 2 'side'");
  EXPECT_LT(at("*FREQUENCY"), down);
  EXPECT_LT(down, side);
  EXPECT_NE(at("*CLOAD, OP=NEW", down), std::string::npos);
  EXPECT_EQ(map.static_steps, 2);
  // The buckling step loads the "side" case: 50 N along y on the box's REF NODE.
  const std::string ref = std::to_string(map.ref_node[0]);
  EXPECT_NE(at("*BUCKLE\n2\n*CLOAD\n" + ref + ", 2, 50\n"), std::string::npos);
  // Six equal masses of 0.5/6 kg in one ELSET, in a rigid body on the box's REF/ROT NODE.
  EXPECT_EQ(map.mass_element_count, 6);
  ASSERT_EQ(map.mass_ref_node.size(), 1u);
  EXPECT_EQ(map.mass_ref_node[0], map.ref_node[0]);
  EXPECT_NE(at("*MASS, ELSET=EMASS1_1\n0.08333333333333"), std::string::npos);
  EXPECT_NE(at("*RIGID BODY, NSET=MASS1, REF NODE=" + ref + ", ROT NODE=" + std::to_string(map.rot_node[0]) + "\n"),
            std::string::npos);
  // Without *FREQUENCY the masses stay out; without load_cases `loads` is the one case.
  std::ostringstream plain;
  const CcxDeckMap pm = write_ccx_deck(test::three_tab_bracket_model(5e-3), plain);
  EXPECT_EQ(pm.mass_element_count, 0);
  EXPECT_EQ(plain.str().find("*MASS"), std::string::npos);
  EXPECT_NE(plain.str().find("** Load case 1 'design'\n*STEP\n*STATIC\n*CLOAD\n"), std::string::npos);
}

TEST(CcxEnvelope, CasesAndOptionsAreCheckedAtTheDoor) {
  ShellModel m = test::three_tab_bracket_model(5e-3);
  m.load_cases = {{"down", {{m.load_node, Vec3(0, 0, -100), Vec3::Zero()}}},
                  {"side", {{m.load_node, Vec3(0, 50, 0), Vec3::Zero()}}}};
  EXPECT_EQ(find_load_case(m, "side"), 1);
  EXPECT_EQ(find_load_case(m, "0"), 0);
  try {
    find_load_case(m, "up");
    ADD_FAILURE() << "no throw";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("the cases: 'down', 'side'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(find_load_case(m, "2"), FemError);
  std::ostringstream sink;
  CcxExportOptions o;
  o.buckle_case = 2;
  EXPECT_THROW(write_ccx_deck(m, sink, o), FemError);
  o.buckle_case = -1;
  o.frequency_modes = 3;
  m.material.density = 0;
  EXPECT_THROW(write_ccx_deck(m, sink, o), FemError);
  m.material.density = 2780;
  m.point_masses = {PointMass{m.load_node, 1.0, Vec3::Zero(), Eigen::Vector3d(3, 1, 1).asDiagonal()}};
  std::ostringstream none;
  EXPECT_THROW(write_ccx_deck(m, none, o), FemError);
  EXPECT_TRUE(none.str().empty());  // checked before a line is written
  // A rigid mass on a sheet node in no link: ccx's rigid body would not follow the sheet's rotation.
  int flange_node = 0;
  while (m.nodes[flange_node].z() > -0.04) ++flange_node;
  m.point_masses = {PointMass{flange_node, 1.0, Vec3::Zero(), Eigen::Matrix3d::Zero()}};
  try {
    write_ccx_deck(m, none, o);
    ADD_FAILURE() << "no throw";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("which is in no rigid link"), std::string::npos) << e.what();
  }
}

// The .dat blocks as ccx 2.20 writes them (copied from its output).
TEST(CcxEnvelope, ReadsDisplacementBlocksBucklingFactorsAndFrequencies) {
  const std::string dir = temp_dir("dat_envelope");
  ASSERT_FALSE(dir.empty());
  const std::string path = dir + "/x.dat";
  std::ofstream(path)
      << "     B U C K L I N G   F A C T O R   O U T P U T\n\n MODE NO       BUCKLING\n                FACTOR\n\n"
         "      1   0.5189741E+03\n      2   0.5191509E+03\n\n"
         "                    E I G E N V A L U E    N U M B E R     1\n\n\n"
         "     E I G E N V A L U E   O U T P U T\n\n"
         " MODE NO    EIGENVALUE                       FREQUENCY   \n"
         "                                     REAL PART            IMAGINARY PART\n"
         "                           (RAD/TIME)      (CYCLES/TIME     (RAD/TIME)\n\n"
         "      1   0.6566486E+02   0.8103386E+01   0.1289694E+01   0.0000000E+00\n"
         "      2   0.1949081E+07   0.1396095E+04   0.2221954E+03   0.0000000E+00\n\n"
         "     P A R T I C I P A T I O N   F A C T O R S\n\n"
         "MODE NO.   X-COMPONENT     Y-COMPONENT     Z-COMPONENT     X-ROTATION      Y-ROTATION      Z-ROTATION\n\n"
         "      1   0.6352657E-13   0.2692593E+01   0.2014840E+01  -0.1222147E-08  -0.1965949E+01   0.2627255E+01\n\n"
         " displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n"
         "         1  0.000000E+00 -2.071432E-25  0.000000E+00\n"
         "         3 -3.242866E-18  1.445087E-03 -6.490383E-11\n\n"
         " displacements (vx,vy,vz) for set NALL and time  0.2000000E+01\n\n"
         "         3 -1.835266E-17 -1.680381E-11  1.445087E-03\n";
  const CcxDatResults r = read_ccx_dat(path);
  ASSERT_EQ(r.buckling_factors.size(), 2u);
  EXPECT_DOUBLE_EQ(r.buckling_factors[0], 518.9741);
  ASSERT_EQ(r.frequencies_hz.size(), 2u);
  EXPECT_DOUBLE_EQ(r.frequencies_hz[0], 1.289694);
  EXPECT_DOUBLE_EQ(r.frequencies_hz[1], 222.1954);
  ASSERT_EQ(r.displacements.size(), 2u);
  EXPECT_EQ(r.displacements[0].set, "NALL");
  EXPECT_DOUBLE_EQ(r.displacements[1].time, 2.0);
  EXPECT_EQ(r.displacements[0].u.size(), 2u);
  EXPECT_DOUBLE_EQ(r.displacements[0].u.at(3).y(), 1.445087e-3);
  EXPECT_DOUBLE_EQ(read_ccx_displacements(path).at(3).z(), 1.445087e-3);  // the last block
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- against ccx

CcxEnvelope run(const ShellModel& m, const std::string& name, const CcxExportOptions& o) {
  const std::string ccx = ccx_path();
  if (ccx.empty())
    throw std::runtime_error("CalculiX (ccx, Debian package calculix-ccx) is required and was not found");
  const std::string dir = temp_dir(name);
  if (dir.empty()) throw std::runtime_error("no temporary directory");
  const CcxEnvelope env = solve_envelope_with_ccx(m, dir, name, ccx, o);
  std::filesystem::remove_all(dir);
  return env;
}

// Clamped-free column: P_cr = pi^2 EI / (4 L^2). nu = 0 makes the plate strip a
// beam; L/t = 100 puts transverse shear at P/(kGA) ~ 1e-5; 20 quadratic S8R
// along L resolve the quarter-wave mode far below 0.1 %. 1 % covers ccx's
// expansion of S8R into one layer of C3D20R (S6: C3D15) through the thickness.
// Both deck elements: S6 is the compliance reference on real parts
// (docs/fem.md "Which CalculiX reference"), S8R the element of the other tests.
TEST(CcxEnvelope, ClampedFreeStripBucklesAtTheEulerLoadInCalculix) {
  for (const char* type : {"S8R", "S6"}) {
    Strip s = cantilever_strip();
    s.model.add_load(s.tip, Vec3(-1, 0, 0));  // 1 N compression: the factor is P_cr in N
    CcxExportOptions o;
    o.element_type = type;
    o.buckle_case = 0;
    o.buckling_factors = 2;
    const CcxEnvelope env = run(s.model, "euler", o);
    const double euler = M_PI * M_PI * s.bending_stiffness() / (4 * s.length * s.length);
    ASSERT_FALSE(env.buckling_factors.empty()) << type;
    std::printf("clamped-free strip: ccx %s buckling factor %.6g, Euler %.6g N (%+.3f %%)\n", type,
                env.buckling_factors[0], euler, 100 * (env.buckling_factors[0] / euler - 1));
    EXPECT_NEAR(env.buckling_factors[0], euler, 0.01 * euler) << type;
    // The static step of the same deck: the end shortens by P L / (E A).
    EXPECT_NEAR(env.cases[0].load_deflection, s.length / (s.youngs_modulus * s.width * s.thickness),
                0.01 * s.length / (s.youngs_modulus * s.width * s.thickness))
        << type;
  }
}

// A 1 kg point mass on the tip of a 2.8 g strip: f = sqrt(k / m_eff) / (2 pi),
// k = 3 EI / L^3, m_eff = m + 33/140 m_strip (Rayleigh's effective mass of a
// cantilever, exact to O((m_strip/m)^2) ~ 1e-5 here). The beam model itself is
// exact for nu = 0 and L/t = 100 (shear ~ (t/L)^2); 0.5 % covers the mesh
// and ccx's C3D20R expansion.
TEST(CcxEnvelope, TipMassOnAStripVibratesAtSqrtKOverMInCalculix) {
  for (const char* type : {"S8R", "S6"}) {
    Strip s = cantilever_strip();
    s.model.add_load(s.tip, Vec3(0, 0, -1));
    s.model.point_masses = {PointMass{s.tip, 1.0, Vec3::Zero(), Eigen::Matrix3d::Zero()}};
    CcxExportOptions o;
    o.element_type = type;
    o.frequency_modes = 3;
    const CcxEnvelope env = run(s.model, "tipmass", o);
    const double k = 3 * s.bending_stiffness() / std::pow(s.length, 3);
    const double f = std::sqrt(k / (1.0 + 33.0 / 140.0 * s.sheet_mass())) / (2 * M_PI);
    ASSERT_GE(env.frequencies_hz.size(), 1u) << type;
    std::printf("tip mass: ccx %s f1 %.6g Hz, sqrt(k/m)/(2 pi) %.6g Hz (%+.3f %%); "
                "static tip %.6g mm, PL^3/3EI %.6g mm\n",
                type, env.frequencies_hz[0], f, 100 * (env.frequencies_hz[0] / f - 1),
                env.cases[0].load_deflection * 1e3, 1e3 / k);
    EXPECT_NEAR(env.frequencies_hz[0], f, 0.005 * f) << type;
    EXPECT_NEAR(env.cases[0].load_deflection, 1 / k, 0.005 / k) << type;
  }
}

// A box (1 kg, 80 x 30 x 70 mm, turned 30 deg about y) whose centre is e = 40
// mm beyond the tip: the tip's deflection w and slope phi carry the box's
// translation w + e phi and rotation phi, so with the cantilever's stiffness
// K = [[L^3/3, L^2/2], [L^2/2, L]]^-1 EI and the box's mass matrix about the
// tip M = [[m, m e], [m e, m e^2 + J_yy]], det(K - w^2 M) = 0 gives the first
// bending frequency. Bending in x-z is uncoupled from the rest by symmetry
// (the turn about y leaves J_xy = J_yz = 0). The strip's mass (0.3 % of the
// box's) moves f by < 0.1 %; 1 % covers that, the mesh and ccx. Without the
// offset f is 70 % higher, without J_yy 5 % higher: both must reach ccx.
TEST(CcxEnvelope, OffsetBoxWithRotaryInertiaVibratesAsTheTwoDofCantileverInCalculix) {
  for (const char* type : {"S8R", "S6"}) {
    Strip s = cantilever_strip();
    s.model.add_load(s.tip, Vec3(0, 0, -1));
    const double m = 1.0, e = 0.04;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 6, Vec3::UnitY()).toRotationMatrix();
    const Eigen::Matrix3d J = R * box_inertia(m, Vec3(0.08, 0.03, 0.07)) * R.transpose();
    s.model.point_masses = {PointMass{s.tip, m, Vec3(e, 0, 0), J}};
    CcxExportOptions o;
    o.element_type = type;
    o.frequency_modes = 3;
    const CcxEnvelope env = run(s.model, "offsetbox", o);
    const double L = s.length, EI = s.bending_stiffness();
    Eigen::Matrix2d flexibility;
    flexibility << L * L * L / 3, L * L / 2, L * L / 2, L;
    const Eigen::Matrix2d K = EI * flexibility.inverse();
    auto first_frequency = [&K](double mass, double offset, double Jyy) {
      Eigen::Matrix2d M;
      M << mass, mass * offset, mass * offset, mass * offset * offset + Jyy;
      const Eigen::Vector2d w2 = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>(K, M).eigenvalues();
      return std::sqrt(w2.minCoeff()) / (2 * M_PI);
    };
    const double f = first_frequency(m, e, J(1, 1));
    const double f_tip = std::sqrt(3 * EI / (L * L * L) / m) / (2 * M_PI);
    const double f_no_inertia = std::sqrt(EI / (L * L * L / 3 + e * L * L + e * e * L) / m) / (2 * M_PI);
    ASSERT_GE(env.frequencies_hz.size(), 1u) << type;
    std::printf("offset box: ccx %s f1 %.6g Hz, two-DOF closed form %.6g Hz (%+.3f %%); mass at the tip %.6g Hz, "
                "at the centre without J %.6g Hz\n",
                type, env.frequencies_hz[0], f, 100 * (env.frequencies_hz[0] / f - 1), f_tip, f_no_inertia);
    EXPECT_NEAR(env.frequencies_hz[0], f, 0.01 * f) << type;
    EXPECT_GT(std::abs(f_tip / f - 1), 0.3);
    EXPECT_GT(std::abs(f_no_inertia / f - 1), 0.03);
  }
}

// Two static cases in one deck (after a *BUCKLE and a *FREQUENCY step, with a
// rigid mass) against one single-case deck each: the same stiffness matrix and
// the same load, so the same numbers up to ccx's 7 printed digits (1e-6 of
// the largest displacement).
TEST(CcxEnvelope, TwoCasesInOneDeckEqualTwoSingleCaseDecksInCalculix) {
  ShellModel m = test::three_tab_bracket_model(5e-3);
  const int box = m.load_node;
  const std::vector<ShellLoadCase> cases = {{"design", m.loads}, {"side", {{box, Vec3(0, 50, 0), Vec3::Zero()}}}};
  m.load_cases = cases;
  m.point_masses = {PointMass{box, 0.5, Vec3::Zero(), box_inertia(0.5, Vec3(0.03, 0.02, 0.03))}};
  CcxExportOptions o;
  o.buckle_case = 0;
  o.frequency_modes = 3;
  const CcxEnvelope both = run(m, "two_cases", o);
  ASSERT_EQ(both.cases.size(), 2u);
  for (size_t c = 0; c < 2; ++c) {
    ShellModel single = m;
    single.load_cases.clear();
    single.point_masses.clear();
    single.loads = cases[c].loads;
    const CcxEnvelope one = run(single, "one_case", CcxExportOptions{});
    double umax = 0, diff = 0;
    for (size_t i = 0; i < m.nodes.size(); ++i) {
      umax = std::max(umax, one.cases[0].displacements[i].cwiseAbs().maxCoeff());
      diff = std::max(diff, (both.cases[c].displacements[i] - one.cases[0].displacements[i]).cwiseAbs().maxCoeff());
    }
    std::printf("case '%s': compliance in one deck %.8g J, alone %.8g J; max |u| difference %.3g of max |u| %.4g m\n",
                cases[c].name.c_str(), both.cases[c].compliance, one.cases[0].compliance, diff / umax, umax);
    EXPECT_EQ(both.cases[c].name, cases[c].name);
    EXPECT_LE(diff, 1e-6 * umax);
    EXPECT_NEAR(both.cases[c].compliance, one.cases[0].compliance, 1e-5 * std::abs(one.cases[0].compliance));
  }
  ASSERT_GE(both.buckling_factors.size(), 1u);
  ASSERT_GE(both.frequencies_hz.size(), 3u);
  std::printf("three-tab bracket: buckling factor of 'design' %.5g, f1..f3 %.5g %.5g %.5g Hz\n",
              both.buckling_factors[0], both.frequencies_hz[0], both.frequencies_hz[1], both.frequencies_hz[2]);
  EXPECT_LE(both.frequencies_hz[0], both.frequencies_hz[1]);
}

}  // namespace
}  // namespace sheetgen
