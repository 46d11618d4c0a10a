#pragma once
// Load cases of a load box (docs/problem-format.md "Load cases"): the explicit
// cases of a load, the inertia cases a box mass gets from the problem's
// acceleration envelope (the FAR/CS 25.561 preset among them), and the box's
// mass properties. Everything here is SI and in the world (scene) frame.
#include <Eigen/Core>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

class JsonNode;

// Standard acceleration of gravity g0, m/s^2 (CGPM 1901, ISO 80000-3): the "g"
// of every load factor.
inline constexpr double kStandardGravity = 9.80665;

// One static load case of a box. Its force acts at the box's centre of mass
// (Load::center_of_mass); its moment is about that point.
struct LoadCase {
  std::string name;                      // unique within its load; one path component
  Vec3 force = Vec3::Zero();             // N, world frame
  Vec3 moment = Vec3::Zero();            // N*m, world frame, about the centre of mass
  std::optional<double> max_deflection;  // m; overrides requirements' stiffness limit for this case
};

// One acceleration of the envelope, in load factors (multiples of g0) along the
// aircraft's axes.
struct InertiaFactor {
  std::string name;                      // becomes the case name on every load with a mass
  Vec3 g = Vec3::Zero();                 // g0, (forward, left, up) components
  std::optional<double> max_deflection;  // m; copied to the cases it makes
};

// The problem-level `load_cases`: the aircraft's axes in the scene and the
// accelerations every box with a mass must be held under, each one separately.
struct InertiaEnvelope {
  Vec3 forward = Vec3::UnitX();  // unit, world
  Vec3 up = Vec3::UnitZ();       // unit, world, exactly orthogonal to forward
  std::string preset;            // "far25.561" when the factors came from a preset, else empty
  std::vector<InertiaFactor> factors;

  // left = up x forward, so that (forward, left, up) is right-handed:
  // forward x left = up (x forward, z up gives y left).
  Vec3 left() const { return up.cross(forward); }
  // A load-factor triple (forward, left, up), g0, as a world direction scaled in g0.
  Vec3 to_world(const Vec3& g) const { return g.x() * forward + g.y() * left() + g.z() * up; }
};

// FAR/CS 25.561(b)(3), emergency landing, ultimate inertia forces acting
// separately: forward 9.0 g, rearward 1.5 g, sideward 3.0 g (airframe) to either
// side, downward 6.0 g, upward 3.0 g. Six factors, in that order.
std::vector<InertiaFactor> far25_561_factors();

// The case a factor makes on a box of `mass` kg: force = mass * g0 * g in the
// envelope's axes (N, world), no moment about the centre of mass.
LoadCase inertia_case(const InertiaEnvelope& envelope, const InertiaFactor& factor, double mass);

// Inertia tensor (kg*m^2, world frame, about the centroid) of a uniform solid
// box of `mass` kg with extents `size` (m) along its local axes, rotated by
// `rotation` (local -> world): R diag(m/12 (b^2+c^2), m/12 (a^2+c^2), m/12 (a^2+b^2)) R^T.
Eigen::Matrix3d uniform_box_inertia(double mass, const Vec3& size, const Eigen::Quaterniond& rotation);

// ------------------------------------------------------------ reading (problem.cpp's helpers)

// The problem-level `load_cases` object. Throws InputError naming the field.
InertiaEnvelope parse_inertia_envelope(const JsonNode& node);

// `loads[i].cases`: explicit cases, names added to `names` (unique per load).
std::vector<LoadCase> parse_explicit_cases(const JsonNode& cases, std::set<std::string>& names);

// `loads[i].inertia`: a symmetric, positive-definite, physically possible 3x3
// tensor (kg*m^2), returned exactly symmetric.
Eigen::Matrix3d parse_inertia(const JsonNode& node);

}  // namespace sheetgen
