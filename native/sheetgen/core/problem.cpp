#include "sheetgen/core/problem.hpp"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/json_reader.hpp"
#include "sheetgen/core/mesh_io.hpp"
#include "sheetgen/core/sheet_gauges.hpp"

namespace sheetgen {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- Load geometry

std::array<Vec3, 8> Load::corners() const {
  std::array<Vec3, 8> c;
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  for (int i = 0; i < 8; ++i) {
    Vec3 local((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(), (i & 4 ? 0.5 : -0.5) * size.z());
    c[i] = center + R * local;
  }
  return c;
}

TriangleMesh Load::box_mesh() const {
  TriangleMesh m;
  const auto c = corners();
  m.vertices.assign(c.begin(), c.end());
  // Quads as corner-index quadruples, counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

double Load::signed_distance(const Vec3& p) const {
  const Vec3 local = rotation.conjugate() * (p - center);
  const Vec3 q = local.cwiseAbs() - 0.5 * size;
  const double outside = q.cwiseMax(Vec3::Zero()).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;
}

std::array<Vec3, 4> Load::bottom_face() const {
  const auto c = corners();
  return {c[0], c[2], c[3], c[1]};  // local z = -size/2; outward normal -z
}

std::optional<double> Requirements::design_frequency_hz() const {
  if (!min_frequency_hz) return std::nullopt;
  return *min_frequency_hz * frequency_model_reserve;
}

namespace {
constexpr double kRightAngleTolerance = 0.5 * M_PI / 180.0;  // rad, either side of 90 deg
constexpr double kRightAngleSkew = 1e-3;                     // rad
}  // namespace

void Manufacturing::restrict_to_right_angles() {
  min_bend_angle = 0.5 * M_PI - kRightAngleTolerance;
  max_bend_angle = 0.5 * M_PI + kRightAngleTolerance;
  max_skew = kRightAngleSkew;
  flat_extensions = true;
}

bool Manufacturing::right_angles_only() const {
  return min_bend_angle >= 0.5 * M_PI - kRightAngleTolerance - 1e-12 &&
         max_bend_angle <= 0.5 * M_PI + kRightAngleTolerance + 1e-12;
}

bool Manufacturing::admits_right_angle_pass() const {
  return !right_angles_only() && min_bend_angle <= 0.5 * M_PI - kRightAngleTolerance &&
         max_bend_angle >= 0.5 * M_PI + kRightAngleTolerance && max_skew >= kRightAngleSkew;
}

double Requirements::compliance_limit(double force_magnitude) const {
  if (max_compliance) return *max_compliance;
  const double deflection = max_deflection ? *max_deflection : 1.0e-3;
  return force_magnitude * deflection;
}

double Requirements::compliance_limit(const LoadCase& load_case) const {
  const double f = load_case.force.norm();
  return load_case.max_deflection ? f * *load_case.max_deflection : compliance_limit(f);
}

BoundingBox Problem::bounds() const {
  BoundingBox b;
  for (const auto& m : meshes) b.extend(bounding_box(m.mesh));
  for (const auto& l : loads)
    for (const auto& c : l.corners()) b.extend(c);
  return b;
}

int Problem::triangle_count() const {
  int n = 0;
  for (const auto& m : meshes) n += static_cast<int>(m.mesh.triangles.size());
  return n;
}

// ---------------------------------------------------------------- parsing

namespace {

TriangleMesh inline_mesh(const JsonNode& node) {
  TriangleMesh mesh;
  const JsonNode verts = node.at("vertices");
  const size_t nv = verts.size();
  mesh.vertices.reserve(nv);
  for (size_t i = 0; i < nv; ++i) mesh.vertices.push_back(verts.at(i).as_vec3());
  const JsonNode tris = node.at("triangles");
  const size_t nt = tris.size();
  mesh.triangles.reserve(nt);
  for (size_t f = 0; f < nt; ++f) {
    const JsonNode t = tris.at(f);
    if (!t.raw().is_array() || t.raw().size() != 3) t.fail("expected an array of 3 vertex indices");
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const JsonNode idx = t.at(k);
      long long v = idx.as_integer();
      if (v < 0 || v >= static_cast<long long>(nv))
        idx.fail("vertex index " + std::to_string(v) + " is out of range (" + std::to_string(nv) + " vertices)");
      tri[k] = static_cast<int>(v);
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

void parse_meshes(const JsonNode& root, const std::string& base_dir, Problem& p) {
  const JsonNode env = root.at("environment");
  env.expect_object();
  reject_unknown(env, {"meshes"});
  const JsonNode meshes = env.at("meshes");
  if (meshes.size() == 0) meshes.fail("the environment has no meshes");
  std::set<std::string> names;
  for (size_t i = 0; i < meshes.size(); ++i) {
    const JsonNode m = meshes.at(i);
    m.expect_object();
    reject_unknown(m, {"name", "file", "vertices", "triangles"});
    EnvironmentMesh em;
    em.name = checked_name(m, names, "mesh");
    if (m.has("file")) {
      if (m.has("vertices") || m.has("triangles")) m.fail("give either 'file' or 'vertices' + 'triangles', not both");
      const JsonNode f = m.at("file");
      const std::string rel = f.as_string();
      if (rel.empty()) f.fail("file name is empty");
      fs::path path = fs::u8path(rel);
      if (path.is_relative()) path = fs::u8path(base_dir) / path;
      em.source = path.u8string();
      std::error_code ec;
      if (!fs::is_regular_file(path, ec))
        f.fail("mesh file '" + em.source + "' does not exist or is not a regular file");
      try {
        em.mesh = read_mesh(em.source);
      } catch (const InputError& e) {
        // Report the mesh file's own error under the JSON field that named it.
        f.fail("cannot read mesh file '" + em.source + "': " + (e.field().empty() ? "" : e.field() + ": ") + e.problem());
      }
      validate_mesh(em.mesh, p.source, m.path() + " (" + em.source + ")");
    } else if (m.has("vertices") || m.has("triangles")) {
      em.source = "<inline>";
      em.mesh = inline_mesh(m);
      validate_mesh(em.mesh, p.source, m.path());
    } else {
      m.fail("needs 'file' or inline 'vertices' and 'triangles'");
    }
    p.meshes.push_back(std::move(em));
  }
}

void parse_rivet_areas(const JsonNode& root, Problem& p) {
  const JsonNode ras = root.at("rivet_areas");
  if (ras.size() == 0) ras.fail("there are no rivet areas: a bracket needs somewhere to be riveted");
  std::set<std::string> names;
  for (size_t i = 0; i < ras.size(); ++i) {
    const JsonNode r = ras.at(i);
    r.expect_object();
    reject_unknown(r, {"name", "mesh", "faces"});
    RivetAreaSpec ra;
    ra.name = checked_name(r, names, "rivet area");
    const JsonNode mesh = r.at("mesh");
    if (mesh.raw().is_string()) {
      const std::string mname = mesh.as_string();
      auto it = std::find_if(p.meshes.begin(), p.meshes.end(), [&](const EnvironmentMesh& m) { return m.name == mname; });
      if (it == p.meshes.end()) mesh.fail("no environment mesh is named '" + mname + "'");
      ra.mesh = static_cast<int>(it - p.meshes.begin());
    } else {
      long long idx = mesh.as_integer();
      if (idx < 0 || idx >= static_cast<long long>(p.meshes.size()))
        mesh.fail("mesh index " + std::to_string(idx) + " is out of range (" + std::to_string(p.meshes.size()) + " meshes)");
      ra.mesh = static_cast<int>(idx);
    }
    const TriangleMesh& target = p.meshes[ra.mesh].mesh;
    const JsonNode faces = r.at("faces");
    if (faces.size() == 0) faces.fail("rivet area '" + ra.name + "' has no faces");
    for (size_t k = 0; k < faces.size(); ++k) {
      const JsonNode fnode = faces.at(k);
      long long f = fnode.as_integer();
      if (f < 0 || f >= static_cast<long long>(target.triangles.size()))
        fnode.fail("face index " + std::to_string(f) + " is out of range (mesh '" + p.meshes[ra.mesh].name + "' has " +
                   std::to_string(target.triangles.size()) + " faces)");
      ra.faces.push_back(static_cast<int>(f));
    }
    std::sort(ra.faces.begin(), ra.faces.end());
    ra.faces.erase(std::unique(ra.faces.begin(), ra.faces.end()), ra.faces.end());
    for (int f : ra.faces) ra.area_m2 += target.face_area(f);
    if (!(ra.area_m2 > 0)) faces.fail("rivet area '" + ra.name + "' has zero area (degenerate faces)");
    // A rivet flange is flat: it can lie flush only on a planar area. Faces
    // whose normals stray more than 10 degrees from the area's mean normal
    // (either side: an open mesh may be wound either way) mean two planes or a
    // curved patch - ask for one area per plane instead of guessing.
    Vec3 mean = Vec3::Zero();
    for (int f : ra.faces) {
      Vec3 n = target.face_normal(f) * target.face_area(f);
      if (mean.dot(n) < 0) n = -n;
      mean += n;
    }
    if (mean.norm() > 0) {
      mean.normalize();
      double worst = 0;
      for (int f : ra.faces) {
        const Vec3 n = target.face_normal(f);
        if (n.norm() == 0) continue;
        worst = std::max(worst, std::acos(std::min(1.0, std::abs(n.dot(mean)))));
      }
      constexpr double kMaxPlanarDeviation = 10.0 * M_PI / 180.0;
      if (worst > kMaxPlanarDeviation)
        faces.fail("rivet area '" + ra.name + "' is not planar (its faces differ by up to " +
                   std::to_string(static_cast<int>(std::lround(worst * 180 / M_PI))) +
                   " degrees from their mean plane); a flange lies flat, so split it into one rivet area per plane");
    }
    // The smallest flange (min_flange long, min_tab_width wide) must fit at least by area.
    const double flange = p.manufacturing.min_flange * p.manufacturing.min_tab_width;
    if (ra.area_m2 < flange) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "rivet area '%s' is %.2f cm^2, smaller than the smallest rivet flange (%.1f x %.1f mm = %.2f cm^2)",
                    ra.name.c_str(), ra.area_m2 * 1e4, p.manufacturing.min_flange * 1e3, p.manufacturing.min_tab_width * 1e3, flange * 1e4);
      faces.fail(buf);
    }
    p.rivet_areas.push_back(std::move(ra));
  }
}

void parse_box(const JsonNode& l, Load& load) {
  load.center = l.at("center").as_vec3();
  const JsonNode size = l.at("size");
  load.size = size.as_vec3();
  if (!(load.size.array() > 0).all())
    size.fail("load box size must be positive in x, y and z, got [" + std::to_string(load.size.x()) + ", " +
              std::to_string(load.size.y()) + ", " + std::to_string(load.size.z()) + "] m");
  if (auto rot = l.find("rotation")) {
    if (!rot->raw().is_array() || rot->raw().size() != 4) rot->fail("expected a quaternion [w, x, y, z]");
    double q[4];
    for (int k = 0; k < 4; ++k) q[k] = rot->at(k).as_number();
    // Scale by the largest component first: squaring 1e200 overflows to inf
    // (normalized() would return a zero quaternion) and 1e-200 underflows to 0.
    const double big = std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2]), std::abs(q[3])});
    if (!(big > 0)) rot->fail("quaternion has zero length");
    Eigen::Quaterniond quat(q[0] / big, q[1] / big, q[2] / big, q[3] / big);
    load.rotation = quat.normalized();
  }
}

// mass, center_of_mass and inertia (docs/problem-format.md "Load cases").
void parse_mass_properties(const JsonNode& l, Load& load) {
  load.center_of_mass = load.center;
  const JsonNode* needs_mass = nullptr;
  std::optional<JsonNode> com = l.find("center_of_mass"), inertia = l.find("inertia");
  if (com) needs_mass = &*com;
  else if (inertia) needs_mass = &*inertia;
  auto m = l.find("mass");
  if (!m) {
    if (needs_mass) needs_mass->fail("is given without 'mass' (kg): give the box's mass too");
    return;
  }
  load.mass = m->as_positive();
  if (com) {
    load.center_of_mass = com->as_vec3();
    // The mass is inside its box; 1 um of slack for coordinates written in float32.
    constexpr double kOutsideTolerance = 1e-6;  // m
    const double outside = load.signed_distance(load.center_of_mass);
    if (outside > kOutsideTolerance)
      com->fail("centre of mass lies " + std::to_string(outside * 1e3) + " mm outside the load box");
  }
  if (inertia) {
    load.inertia = parse_inertia(*inertia);
  } else {
    load.inertia = uniform_box_inertia(*load.mass, load.size, load.rotation);
    // Only absurd masses or sizes (1e300 kg, 1e-200 m) overflow or vanish here.
    if (!load.inertia.allFinite() || !(load.inertia.diagonal().array() > 0).all())
      m->fail("the uniform box inertia of this mass and size is not finite and positive; give 'inertia'");
  }
}

// A case of the load itself carries the name of an envelope factor: name the
// load's own field, which the user can rename.
[[noreturn]] void duplicate_of_factor(const JsonNode& l, const Load& load, const std::string& name) {
  const std::string problem = "case name '" + name + "' is also a factor of load_cases; names must be unique per load";
  if (auto cases = l.find("cases"))
    for (size_t k = 0; k < load.cases.size(); ++k)
      if (load.cases[k].name == name) cases->at(k).at("name").fail(problem);
  l.at("force").fail("the case of 'force' is named '" + name + "', which is also a factor of load_cases; rename the factor");
}

// `cases`, or `force`/`moment` as the case "design"; then one case per factor
// of the problem's `load_cases` when the box has a mass.
void parse_cases(const JsonNode& l, const std::optional<InertiaEnvelope>& envelope, Load& load) {
  std::set<std::string> names;
  const bool inertia = load.mass && envelope;
  if (auto cases = l.find("cases")) {
    for (const char* key : {"force", "moment"})
      if (l.has(key)) l.at(key).fail("give either 'cases' or 'force'/'moment', not both");
    load.cases = parse_explicit_cases(*cases, names);
  } else if (l.has("force") || l.has("moment") || !inertia) {
    if (!l.has("force"))  // the message names what else would do
      throw InputError(l.file(), l.path() + ".force",
                       "required field is missing (or give 'cases', or a 'mass' with a problem-level 'load_cases')");
    const JsonNode force = l.at("force");
    LoadCase design{"design", force.as_vec3(), Vec3::Zero(), std::nullopt};
    if (auto m = l.find("moment")) design.moment = m->as_vec3();
    if (design.force.norm() == 0 && design.moment.norm() == 0) force.fail("load '" + load.name + "' has zero force and zero moment");
    names.insert(design.name);
    load.cases.push_back(std::move(design));
  }
  if (inertia) {
    for (const InertiaFactor& f : envelope->factors) {
      if (!names.insert(f.name).second) duplicate_of_factor(l, load, f.name);
      LoadCase c = inertia_case(*envelope, f, *load.mass);
      if (!c.force.allFinite()) l.at("mass").fail("mass times factor '" + f.name + "' gives a force that is not finite");
      load.cases.push_back(std::move(c));
    }
  }
  load.force = load.cases.front().force;
  load.moment = load.cases.front().moment;
}

void parse_loads(const JsonNode& root, Problem& p) {
  const JsonNode loads = root.at("loads");
  if (loads.size() == 0) loads.fail("there are no loads: nothing to hold");
  std::set<std::string> names;
  for (size_t i = 0; i < loads.size(); ++i) {
    const JsonNode l = loads.at(i);
    l.expect_object();
    reject_unknown(l, {"name", "center", "size", "rotation", "force", "moment", "mass", "center_of_mass", "inertia", "cases"});
    Load load;
    load.name = checked_name(l, names, "load");
    parse_box(l, load);
    parse_mass_properties(l, load);
    parse_cases(l, p.load_cases, load);
    p.loads.push_back(load);
  }
}

// The problem-level inertia envelope; read before the loads, which it expands.
void parse_envelope(const JsonNode& root, Problem& p) {
  if (auto env = root.find("load_cases")) p.load_cases = parse_inertia_envelope(*env);
}

// An envelope that reaches no box is a forgotten mass, not a choice: refuse it
// rather than design parts that ignore it.
void check_envelope_used(const JsonNode& root, const Problem& p) {
  if (!p.load_cases) return;
  if (std::none_of(p.loads.begin(), p.loads.end(), [](const Load& l) { return l.mass.has_value(); }))
    root.at("load_cases").fail("applies to loads with a 'mass' (kg) and no load has one; give the boxes their mass");
}

// Whether the file asks for the checks beyond one static case: it uses the
// envelope format or names a buckling or frequency floor.
bool uses_envelope(const JsonNode& root) {
  if (root.has("load_cases")) return true;
  if (auto r = root.find("requirements"); r && (r->has("min_buckling_factor") || r->has("min_frequency_hz"))) return true;
  const JsonNode loads = root.at("loads");
  for (size_t i = 0; i < loads.size(); ++i)
    if (loads.at(i).has("mass") || loads.at(i).has("cases")) return true;
  return false;
}

// The buckling floor defaults to the safety factor read just before it.
void parse_requirements(const JsonNode& root, Requirements& req) {
  auto r = root.find("requirements");
  if (!r) return;
  r->expect_object();
  reject_unknown(*r, {"max_compliance", "max_deflection", "min_margin_of_safety", "safety_factor", "clearance",
                      "min_buckling_factor", "min_frequency_hz"});
  if (auto c = r->find("max_compliance")) req.max_compliance = c->as_positive();
  if (auto d = r->find("max_deflection")) req.max_deflection = d->as_positive();
  if (req.max_compliance && req.max_deflection) r->fail("give max_compliance or max_deflection, not both");
  req.min_margin_of_safety = r->number_or("min_margin_of_safety", req.min_margin_of_safety);
  req.safety_factor = r->positive_or("safety_factor", req.safety_factor);
  req.clearance = r->non_negative_or("clearance", req.clearance);
  req.min_buckling_factor = r->positive_or("min_buckling_factor", req.safety_factor);
  if (auto f = r->find("min_frequency_hz")) req.min_frequency_hz = f->as_positive();
}

// material.gauges (m), when the file gives them: ascending, each thicker
// than material.thickness. The default is parse_problem's.
void parse_gauges(const JsonNode& root, Material& mat) {
  std::optional<JsonNode> m = root.find("material");
  std::optional<JsonNode> g = m ? m->find("gauges") : std::nullopt;
  if (!g) return;
  g->expect_array();
  mat.gauges.clear();
  for (size_t k = 0; k < g->size(); ++k) {
    const JsonNode e = g->at(k);
    const double v = e.as_positive();
    if (v <= mat.thickness) {
      char t[32];
      std::snprintf(t, sizeof t, "%.4g", mat.thickness);
      e.fail(std::string("must be thicker than material.thickness (") + t + " m): gauges are the thicker sheets tried "
             "when the problem's sheet gives a load no part");
    }
    if (!mat.gauges.empty() && v <= mat.gauges.back()) e.fail("gauges must be listed thinnest first, each once");
    mat.gauges.push_back(v);
  }
}

void parse_settings(const JsonNode& root, Problem& p) {
  if (auto m = root.find("material")) {
    m->expect_object();
    reject_unknown(*m, {"name", "youngs_modulus", "poisson_ratio", "density", "yield_strength", "ultimate_strength", "thickness",
                        "gauges"});
    Material& mat = p.material;
    mat.youngs_modulus = m->positive_or("youngs_modulus", mat.youngs_modulus);
    mat.poisson_ratio = m->number_or("poisson_ratio", mat.poisson_ratio);
    if (!(mat.poisson_ratio > -1 && mat.poisson_ratio < 0.5)) m->at("poisson_ratio").fail("must lie in (-1, 0.5)");
    mat.density = m->positive_or("density", mat.density);
    mat.yield_strength = m->positive_or("yield_strength", mat.yield_strength);
    mat.ultimate_strength = m->positive_or("ultimate_strength", mat.ultimate_strength);
    mat.thickness = m->positive_or("thickness", mat.thickness);
  }
  parse_gauges(root, p.material);
  const double t = p.material.thickness;
  parse_requirements(root, p.requirements);
  Manufacturing& mf = p.manufacturing;
  std::optional<JsonNode> m = root.find("manufacturing");
  if (m) {
    m->expect_object();
    reject_unknown(*m, {"bend_radius", "k_factor", "kerf", "min_flange", "min_tab_width", "min_tab_length", "max_tab_length",
                        "min_bend_angle", "max_bend_angle", "max_skew", "rivet_diameter", "rivet_edge_distance", "rivet_pitch",
                        "press_brake", "press_brake_tools"});
    if (std::optional<JsonNode> pb = m->find("press_brake")) {
      const std::string use = pb->as_string();
      if (use != "report" && use != "prefer" && use != "require")
        pb->fail("must be \"report\", \"prefer\" or \"require\", got \"" + use + "\"");
      mf.press_brake_required = use != "report";
      mf.press_brake_fallback = use == "prefer";
    }
    if (std::optional<JsonNode> tools = m->find("press_brake_tools")) parse_press_brake_tooling(*tools, mf.press_brake_tools);
  }
  auto pos = [&](const char* key, double fallback) { return m ? m->positive_or(key, fallback) : fallback; };
  auto nonneg = [&](const char* key, double fallback) { return m ? m->non_negative_or(key, fallback) : fallback; };
  // The lengths that scale with t: kept as given, so a thicker gauge derives its own.
  auto given = [&](const char* key, bool zero_ok) -> std::optional<double> {
    std::optional<JsonNode> n = m ? m->find(key) : std::nullopt;
    if (!n) return std::nullopt;
    return zero_ok ? n->as_non_negative() : n->as_positive();
  };
  ThicknessScaledInput& in = mf.given;
  in.bend_radius = given("bend_radius", true);
  in.min_flange = given("min_flange", false);
  in.min_tab_width = given("min_tab_width", false);
  in.min_tab_length = given("min_tab_length", false);
  in.rivet_diameter = given("rivet_diameter", false);
  in.rivet_edge_distance = given("rivet_edge_distance", false);
  in.rivet_pitch = given("rivet_pitch", false);
  derive_thickness_defaults(mf, t);
  mf.k_factor = nonneg("k_factor", mf.k_factor);
  if (mf.k_factor > 1.0) m->at("k_factor").fail("must lie in [0, 1]");
  mf.kerf = nonneg("kerf", mf.kerf);
  mf.max_tab_length = pos("max_tab_length", mf.max_tab_length);
  if (mf.max_tab_length < mf.min_tab_length) (m ? m->at("max_tab_length") : root).fail("max_tab_length is below min_tab_length");
  mf.min_bend_angle = pos("min_bend_angle", mf.min_bend_angle);
  mf.max_bend_angle = pos("max_bend_angle", mf.max_bend_angle);
  if (mf.max_bend_angle > M_PI || mf.max_bend_angle < mf.min_bend_angle)
    (m ? m->at("max_bend_angle") : root).fail("must lie between min_bend_angle and pi (radians)");
  mf.max_skew = nonneg("max_skew", mf.max_skew);

  if (auto c = root.find("cost")) parse_cost_model(*c, p.cost);

  if (auto s = root.find("search")) {
    s->expect_object();
    reject_unknown(*s, {"chains", "iterations", "beam_width", "seed", "alpha", "beta", "scene_unit", "threads"});
    SearchSettings& ss = p.search;
    auto count = [&](const char* key, int fallback, long long lo, long long hi) {
      auto n = s->find(key);
      if (!n) return fallback;
      long long v = n->as_integer();
      if (v < lo || v > hi) n->fail("must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
      return static_cast<int>(v);
    };
    ss.chains = count("chains", ss.chains, 1, 1024);
    ss.iterations = count("iterations", ss.iterations, 0, 10000000);
    ss.beam_width = count("beam_width", ss.beam_width, 1, 4096);
    ss.threads = count("threads", ss.threads, 0, 1024);
    if (auto seed = s->find("seed")) {
      long long v = seed->as_integer();
      if (v < 0) seed->fail("must not be negative");
      ss.seed = static_cast<std::uint64_t>(v);
    }
    ss.alpha = s->non_negative_or("alpha", ss.alpha);
    ss.beta = s->non_negative_or("beta", ss.beta);
    ss.scene_unit = s->positive_or("scene_unit", ss.scene_unit);
  }
}

// A scene exported from a CAD or Blender file in millimetres reads as a scene
// a thousand times too big: a 160 mm box becomes 160 m. Metre-scale brackets
// never hold a box larger than 10 m in a scene spanning over 100 m, so that
// combination is refused with the likely cause (docs/reliability.md).
void check_scale(const JsonNode& root, const Problem& p) {
  constexpr double kMaxSceneDiagonal = 100.0;  // m
  constexpr double kMaxLoadSize = 10.0;        // m, largest box extent
  const double diagonal = p.bounds().diagonal();
  if (!(diagonal > kMaxSceneDiagonal)) return;
  for (size_t i = 0; i < p.loads.size(); ++i) {
    const double largest = p.loads[i].size.maxCoeff();
    if (largest > kMaxLoadSize) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "load box is %.4g m across in a scene %.4g m across: the file looks like it is in millimetres "
                    "(problem files are in metres; scale the scene by 0.001)",
                    largest, diagonal);
      root.at("loads").at(i).at("size").fail(buf);
    }
  }
}

}  // namespace

namespace {

// Python's json module writes NaN, Infinity and -Infinity, which JSON does not
// allow. Rather than a parse error at a byte offset, turn them into marked
// strings so the field that holds one is named in the error.
std::string mark_non_finite_tokens(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) out += text[++i];
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
      out += c;
      continue;
    }
    bool matched = false;
    for (const char* token : {"-Infinity", "Infinity", "NaN"}) {
      const size_t n = std::strlen(token);
      if (text.compare(i, n, token) == 0) {
        out += std::string("\"") + kNonFiniteMarker + token + "\"";
        i += n - 1;
        matched = true;
        break;
      }
    }
    if (!matched) out += c;
  }
  return out;
}

}  // namespace

Problem parse_problem(const std::string& json_text, const std::string& source, const std::string& base_dir) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(mark_non_finite_tokens(json_text));
  } catch (const nlohmann::json::exception& e) {
    // parse_error, and out_of_range 406 for a number literal beyond double
    // (1e999). e.what() carries byte position and reason; keep the part after the id.
    std::string what = e.what();
    auto pos = what.find("] ");
    throw InputError(source, "", "is not valid JSON (" + (pos == std::string::npos ? what : what.substr(pos + 2)) + ")");
  }
  Problem p;
  p.source = source;
  const JsonNode root(doc, source, "");
  root.expect_object();
  reject_unknown(root, {"format", "name", "description", "units", "environment", "rivet_areas", "loads", "material",
                        "load_cases", "requirements", "manufacturing", "cost", "search"});
  const JsonNode format = root.at("format");
  if (format.as_string() != "sheetgen-problem/1")
    format.fail("unsupported format '" + format.as_string() + "' (expected 'sheetgen-problem/1')");
  if (auto units = root.find("units"))
    if (units->as_string() != "m") units->fail("only 'm' (metres) is supported; scale the scene to metres");
  parse_settings(root, p);  // first: defaults of manufacturing depend on thickness
  parse_meshes(root, base_dir, p);
  parse_rivet_areas(root, p);
  parse_envelope(root, p);
  parse_loads(root, p);
  check_envelope_used(root, p);
  check_scale(root, p);
  p.requirements.eigen_checks = uses_envelope(root);
  // Gauges not given: the standard ones above the sheet for a file in the
  // envelope format; none for a file with one force per load, which solves
  // as it was written for, in its own sheet (docs/problem-format.md).
  const std::optional<JsonNode> material = root.find("material");
  if (!(material && material->has("gauges")))
    p.material.gauges = p.requirements.eigen_checks ? default_gauges(p.material.thickness) : std::vector<double>{};
  return p;
}

Problem load_problem(const std::string& path) {
  std::error_code ec;
  const fs::path fpath = fs::u8path(path);
  if (!fs::exists(fpath, ec)) throw InputError(path, "", "file does not exist");
  if (!fs::is_regular_file(fpath, ec)) throw InputError(path, "", "is not a regular file");
  // A problem file is small: the meshes live in their own files. Refuse
  // anything huge before reading it into memory.
  const auto size = fs::file_size(fpath, ec);
  constexpr std::uintmax_t kMaxProblemBytes = 256ull << 20;
  if (!ec && size > kMaxProblemBytes)
    throw InputError(path, "", "is " + std::to_string(size >> 20) + " MiB; problem files are limited to 256 MiB (put large meshes in OBJ/PLY files)");
  std::ifstream in(fpath, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot be opened");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string base = fpath.has_parent_path() ? fpath.parent_path().u8string() : std::string(".");
  return parse_problem(ss.str(), path, base);
}

}  // namespace sheetgen
