#include "sheetgen/core/load_cases.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sheetgen/core/json_reader.hpp"

namespace sheetgen {

std::vector<InertiaFactor> far25_561_factors() {
  // 14 CFR 25.561(b)(3) (CS 25.561(b)(3) is the same): ultimate inertia forces
  // relative to the surrounding structure, applied separately. Sideward is the
  // airframe's 3.0 g (4.0 g is for seats), applied to either side.
  return {
      {"forward 9 g", Vec3(9.0, 0, 0), std::nullopt},   {"rearward 1.5 g", Vec3(-1.5, 0, 0), std::nullopt},
      {"left 3 g", Vec3(0, 3.0, 0), std::nullopt},      {"right 3 g", Vec3(0, -3.0, 0), std::nullopt},
      {"down 6 g", Vec3(0, 0, -6.0), std::nullopt},     {"up 3 g", Vec3(0, 0, 3.0), std::nullopt},
  };
}

LoadCase inertia_case(const InertiaEnvelope& envelope, const InertiaFactor& factor, double mass) {
  LoadCase c;
  c.name = factor.name;
  c.force = mass * kStandardGravity * envelope.to_world(factor.g);
  c.max_deflection = factor.max_deflection;
  return c;
}

Eigen::Matrix3d uniform_box_inertia(double mass, const Vec3& size, const Eigen::Quaterniond& rotation) {
  const Vec3 sq = size.cwiseProduct(size);
  const Vec3 principal = mass / 12.0 * Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y());
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  return R * principal.asDiagonal() * R.transpose();
}

// ------------------------------------------------------------ reading

namespace {

// Tolerance on |cos| between forward and up after normalising, and on the
// relative asymmetry of an inertia tensor: far above the 1e-7 relative error of
// numbers a float32 tool (Blender) writes, far below any intended angle (1e-6
// rad is 0.2 arc seconds).
constexpr double kAxisTolerance = 1e-6;

// A direction given as [x, y, z], normalised; fails on a zero vector.
Vec3 unit_direction(const JsonNode& node) {
  const Vec3 v = node.as_vec3();
  // Scale by the largest component first so 1e200 or 1e-200 neither overflows nor underflows.
  const double big = v.cwiseAbs().maxCoeff();
  if (!(big > 0)) node.fail("direction has zero length");
  return (v / big).normalized();
}

std::vector<InertiaFactor> parse_factors(const JsonNode& node) {
  std::vector<InertiaFactor> out;
  std::set<std::string> names;
  for (size_t k = 0; k < node.size(); ++k) {
    const JsonNode f = node.at(k);
    f.expect_object();
    reject_unknown(f, {"name", "g", "max_deflection"});
    InertiaFactor factor;
    factor.name = checked_name(f, names, "factor");
    const JsonNode g = f.at("g");
    factor.g = g.as_vec3();
    if (factor.g.isZero(0)) g.fail("factor '" + factor.name + "' is [0, 0, 0] g: a case with no force and no moment");
    if (auto d = f.find("max_deflection")) factor.max_deflection = d->as_positive();
    out.push_back(std::move(factor));
  }
  return out;
}

}  // namespace

InertiaEnvelope parse_inertia_envelope(const JsonNode& node) {
  node.expect_object();
  reject_unknown(node, {"forward", "up", "factors"});
  InertiaEnvelope env;
  env.forward = unit_direction(node.at("forward"));
  const JsonNode up = node.at("up");
  env.up = unit_direction(up);
  const double cosine = env.forward.dot(env.up);
  if (std::abs(cosine) > kAxisTolerance) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "forward and up are not orthogonal (%.6g degrees apart, |cos| = %.3g > %.0e)",
                  std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI, std::abs(cosine), kAxisTolerance);
    up.fail(buf);
  }
  // Remove the tolerated sliver of forward so (forward, left, up) is exactly orthonormal.
  env.up = (env.up - cosine * env.forward).normalized();

  const JsonNode factors = node.at("factors");
  if (factors.raw().is_string()) {
    env.preset = factors.as_string();
    if (env.preset != "far25.561") factors.fail("unknown preset '" + env.preset + "' (the one preset is 'far25.561')");
    env.factors = far25_561_factors();
  } else if (factors.raw().is_array()) {
    if (factors.size() == 0) factors.fail("no factors: give at least one, or the preset 'far25.561'");
    env.factors = parse_factors(factors);
  } else {
    factors.fail("expected the preset name 'far25.561' or an array of factors");
  }
  return env;
}

std::vector<LoadCase> parse_explicit_cases(const JsonNode& cases, std::set<std::string>& names) {
  if (cases.size() == 0) cases.fail("no cases: give at least one, or 'force'");
  std::vector<LoadCase> out;
  for (size_t k = 0; k < cases.size(); ++k) {
    const JsonNode c = cases.at(k);
    c.expect_object();
    reject_unknown(c, {"name", "force", "moment", "max_deflection"});
    LoadCase lc;
    lc.name = checked_name(c, names, "case");
    if (auto f = c.find("force")) lc.force = f->as_vec3();
    if (auto m = c.find("moment")) lc.moment = m->as_vec3();
    if (lc.force.isZero(0) && lc.moment.isZero(0)) c.fail("case '" + lc.name + "' has no force and no moment");
    if (auto d = c.find("max_deflection")) lc.max_deflection = d->as_positive();
    out.push_back(std::move(lc));
  }
  return out;
}

Eigen::Matrix3d parse_inertia(const JsonNode& node) {
  if (!node.raw().is_array() || node.raw().size() != 3) node.fail("expected a 3x3 array (3 rows of 3 numbers), kg*m^2");
  Eigen::Matrix3d I;
  for (int r = 0; r < 3; ++r) I.row(r) = node.at(r).as_vec3().transpose();
  const double scale = I.cwiseAbs().maxCoeff();
  if (!(scale > 0)) node.fail("inertia is all zeros: not positive definite");
  const Eigen::Matrix3d S = I / scale;  // scaled: 1e300 entries neither overflow nor lose the test
  for (int r = 0; r < 3; ++r)
    for (int c = r + 1; c < 3; ++c)
      if (std::abs(S(r, c) - S(c, r)) > kAxisTolerance) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "inertia is not symmetric: [%d][%d] = %.6g but [%d][%d] = %.6g", r, c, I(r, c), c, r, I(c, r));
        node.fail(buf);
      }
  const Eigen::Matrix3d sym = 0.5 * (S + S.transpose());
  const Vec3 p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sym, Eigen::EigenvaluesOnly).eigenvalues() * scale;
  char moments[120];
  std::snprintf(moments, sizeof moments, "principal moments %.6g, %.6g, %.6g kg*m^2", p[0], p[1], p[2]);
  if (!(p[0] > 0)) node.fail(std::string("inertia is not positive definite (") + moments + ")");
  // A rigid body's principal moments obey I3 <= I1 + I2 (equality for a flat
  // plate): a tensor that breaks it is a typo, not a box.
  if (p[2] > (p[0] + p[1]) * (1 + kAxisTolerance))
    node.fail(std::string("inertia is not that of a rigid body (") + moments + ": the largest exceeds the sum of the other two)");
  return sym * scale;
}

}  // namespace sheetgen
