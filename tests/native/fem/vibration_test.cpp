// Natural frequencies against closed forms (docs/fem.md "Natural frequencies").
#include "sheetgen/fem/vibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/shell_mass.hpp"
#include "strip_models.hpp"

namespace sheetgen {
namespace {

using test::strip;

double strip_ei(const test::Strip& s) {
  const Material& m = s.model.material;
  return m.youngs_modulus * s.width * std::pow(m.thickness, 3) / 12.0;
}

double strip_mass(const test::Strip& s) {
  const Material& m = s.model.material;
  return m.density * m.thickness * s.width * s.length;
}

// A cantilever strip's first bending mode: f1 = (1.8751^2 / 2 pi) sqrt(EI / (rho A L^4))
// (Euler-Bernoulli; nu = 0 so the plate is the beam).
TEST(Vibration, CantileverStripFirstBendingMatchesBeam) {
  test::Strip s = strip(60, 4);
  for (int n : s.grid.front()) s.model.clamp(n);
  ShellSolver solver;
  const VibrationResult v = analyse_vibration(solver, s.model);
  const double rho_a = strip_mass(s) / s.length;  // kg/m
  const double beta = 1.87510407;
  const double closed = beta * beta / (2 * M_PI) * std::sqrt(strip_ei(s) / (rho_a * std::pow(s.length, 4)));
  ASSERT_EQ(v.frequencies_hz.size(), 3u);
  std::printf("cantilever strip: f1 %.6g Hz, beam %.6g Hz, ratio %.4f\n", v.frequencies_hz[0], closed, v.frequencies_hz[0] / closed);
  EXPECT_NEAR(v.frequencies_hz[0] / closed, 1.0, 0.02);
  EXPECT_NEAR(v.sheet_mass / strip_mass(s), 1.0, 1e-12);
}

// The strip's tip rigidly tied to a master carrying a mass 100 x the strip's:
// f = sqrt(k / m) / 2 pi with the tip stiffness k = 3 EI / L^3 (the strip's
// own mass adds 0.24 % of its mass to m: 0.1 % on f).
TEST(Vibration, RigidMassOnSlenderStripMatchesSpringMass) {
  test::Strip s = strip(60, 4);
  ShellModel& m = s.model;
  for (int n : s.grid.front()) m.clamp(n);
  const int master = m.add_node(Vec3(s.length, s.width / 2, 0));
  m.rigid_links.push_back(RigidLink{master, s.grid.back()});
  PointMass box;
  box.node = master;
  box.mass = 100 * strip_mass(s);
  m.point_masses.push_back(box);
  ShellSolver solver;
  const VibrationResult v = analyse_vibration(solver, m);
  const double k = 3 * strip_ei(s) / std::pow(s.length, 3);
  const double closed = std::sqrt(k / box.mass) / (2 * M_PI);
  std::printf("mass on strip: f1 %.6g Hz, sqrt(k/m)/2pi %.6g Hz, ratio %.4f\n", v.frequencies_hz[0], closed, v.frequencies_hz[0] / closed);
  EXPECT_NEAR(v.frequencies_hz[0] / closed, 1.0, 0.02);
  EXPECT_DOUBLE_EQ(v.point_mass, box.mass);
}

// The same body as a PointMass with an offset and inertia, and as its mass at
// a node placed at the offset (rigidly tied) with the same inertia: identical
// mass matrices, so identical frequencies.
TEST(Vibration, OffsetPointMassEqualsMassAtTheOffsetNode) {
  auto model = [](bool offset_form) {
    test::Strip s = strip(30, 2);
    ShellModel& m = s.model;
    for (int n : s.grid.front()) m.clamp(n);
    const int master = m.add_node(Vec3(s.length, s.width / 2, 0));
    const Vec3 r(0.03, -0.01, 0.04);
    std::vector<int> slaves = s.grid.back();
    const int at_offset = m.add_node(m.nodes[master] + r);
    slaves.push_back(at_offset);
    m.rigid_links.push_back(RigidLink{master, slaves});
    PointMass p;
    p.mass = 0.5;
    p.inertia = Eigen::Vector3d(2e-4, 3e-4, 1e-4).asDiagonal();
    p.node = offset_form ? master : at_offset;
    p.offset = offset_form ? r : Vec3::Zero();
    m.point_masses.push_back(p);
    return m;
  };
  ShellSolver a, b;
  const VibrationResult va = analyse_vibration(a, model(true));
  const VibrationResult vb = analyse_vibration(b, model(false));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(va.frequencies_hz[k] / vb.frequencies_hz[k], 1.0, 1e-9);
}

// The rigid-body mass matrix moves the body's kinetic energy exactly: for a
// node velocity (v, w), T = m/2 |v + w x r|^2 + 1/2 w^T J w.
TEST(Vibration, RigidBodyMassGivesTheKineticEnergy) {
  PointMass p;
  p.mass = 2.0;
  p.offset = Vec3(0.1, -0.2, 0.3);
  p.inertia << 0.02, 0.001, 0, 0.001, 0.03, 0.002, 0, 0.002, 0.04;
  const Eigen::Matrix<double, 6, 6> M = rigid_body_mass(p);
  Vector6d q;
  q << 0.3, -1.0, 0.7, 2.0, -0.5, 1.5;
  const Vec3 v = q.head<3>(), w = q.tail<3>();
  const double energy = 0.5 * p.mass * (v + w.cross(p.offset)).squaredNorm() + 0.5 * w.dot(p.inertia * w);
  EXPECT_NEAR(0.5 * q.dot(M * q), energy, 1e-12 * energy);
  EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Vibration, BadMassesAreNamed) {
  test::Strip s = strip(10, 2);
  for (int n : s.grid.front()) s.model.clamp(n);
  ShellSolver solver;
  for (double mass : {0.0, -1.0, std::nan("")}) {
    ShellModel m = s.model;
    PointMass p;
    p.node = s.grid.back()[0];
    p.mass = mass;
    m.point_masses.push_back(p);
    try {
      analyse_vibration(solver, m);
      ADD_FAILURE() << "mass " << mass << " accepted";
    } catch (const FemError& e) {
      EXPECT_EQ(e.field(), "point_masses[0].mass") << e.what();
    }
  }
  ShellModel m = s.model;
  m.material.density = 0;
  EXPECT_THROW(analyse_vibration(solver, m), FemError);
}

// A strip held at one node only rotates freely about it: K is singular and the
// analysis says so instead of returning 0 Hz, NaN or hanging.
TEST(Vibration, MechanismIsAnErrorNotANaN) {
  test::Strip s = strip(10, 2);
  NodeSupport pin{s.grid.front()[0]};
  pin.fixed = {true, true, true, false, false, false};
  s.model.supports.push_back(pin);
  ShellSolver solver;
  try {
    analyse_vibration(solver, s.model);
    ADD_FAILURE() << "a mechanism was analysed";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("mechanism"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sheetgen
