#include "sheetgen/structure/part_model.hpp"

#include "sheetgen/structure/envelope_analysis.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/json_reader.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/rivet_layout.hpp"

namespace sheetgen {

PlateGeometry plate_geometry(const Part& part, const RealisedPart& realised) {
  PlateGeometry g;
  for (int i = 0; i < part.size(); ++i) {
    g.polygons.push_back(realised.tabs[i].corners);
    g.rivet_area.push_back(part.tabs[i].rivet_area);
    g.rivet_edge.push_back(i == 0 ? 0 : kFarEdge);
    g.parent.push_back(i == 0 ? -1 : part.tabs[i].parent);
    g.bend_angle.push_back(i == 0 ? 0.0 : std::abs(part.tabs[i].params.theta3));
  }
  return g;
}

namespace {

// The rectangle in polygon `into`'s plane along segment [a, b], extended by
// `extend` beyond both ends and `depth` deep into the polygon (m).
std::vector<Vec3> strip(const std::vector<Vec3>& into, const Vec3& a, const Vec3& b, double extend, double depth) {
  Vec3 n = Vec3::Zero(), c = Vec3::Zero();
  for (size_t i = 0; i < into.size(); ++i) {
    n += into[i].cross(into[(i + 1) % into.size()]);
    c += into[i] / static_cast<double>(into.size());
  }
  const Vec3 u = (b - a).normalized();
  Vec3 v = n.normalized().cross(u);
  if (v.dot(c - a) < 0) v = -v;  // towards the polygon
  const Vec3 p = a - extend * u, q = b + extend * u;
  return {p, q, q + depth * v, p + depth * v};
}

// The larger |tan| of the angle between a tab's side edges and the normal to
// its root (corners 0-1): 0 for a square tab.
double side_skew(const std::vector<Vec3>& tab) {
  if (tab.size() < 4) return 0.0;
  const Vec3 u = (tab[1] - tab[0]).normalized();
  double skew = 0;
  for (const Vec3& side : {Vec3(tab.back() - tab[0]), Vec3(tab[2] - tab[1])}) {
    const double along = side.dot(u), across = (side - along * u).norm();
    if (across > 0) skew = std::max(skew, std::abs(along) / across);
  }
  return skew;
}

}  // namespace

std::vector<std::vector<Vec3>> bend_keep_out(const PlateGeometry& g, int k, const SheetSpec& sheet) {
  std::vector<std::vector<Vec3>> zones;
  if (g.parent.size() != g.polygons.size() || g.bend_angle.size() != g.polygons.size()) return zones;
  const auto& poly = g.polygons[k];
  // Its own root: the bend zone reaches the setback SB into it along the whole
  // edge (extended by the polygon's size: the zone is a half-plane for it).
  if (g.parent[k] >= 0 && g.bend_angle[k] > 0 && poly.size() >= 2) {
    double size = 0;
    for (const Vec3& p : poly) size = std::max(size, (p - poly[0]).norm());
    zones.push_back(strip(poly, poly[0], poly[1], size, bend_setback(g.bend_angle[k], sheet)));
  }
  // Each bent child: its bend zone on this polygon's edge, with the relief
  // notches cut beside it (width t, bend_zone_depth deep; FlatPatternOptions).
  // A skewed child's notches follow its side edges into this polygon, so they
  // reach depth * tan(skew) further along the edge than a square notch.
  for (size_t c = 0; c < g.polygons.size(); ++c) {
    if (g.parent[c] != k || !(g.bend_angle[c] > 0) || g.polygons[c].size() < 2) continue;
    const double depth = bend_zone_depth(g.bend_angle[c], sheet);
    zones.push_back(strip(poly, g.polygons[c][0], g.polygons[c][1], sheet.thickness + depth * side_skew(g.polygons[c]),
                          depth));
  }
  return zones;
}

namespace {

void check_part_model_inputs(const Problem& problem, int load_index, const PlateGeometry& geometry) {
  if (load_index < 0 || load_index >= static_cast<int>(problem.loads.size()))
    throw FemError("load", "index " + std::to_string(load_index) + " is out of range");
  const double t = problem.material.thickness;
  if (!(t > 0)) throw FemError("material.thickness", "must be > 0 (got " + std::to_string(t) + " m)");
  if (geometry.polygons.empty()) throw FemError("part", "has no tabs");
}

RivetLayoutOptions flange_rivet_options(const Problem& problem) {
  const Manufacturing& mf = problem.manufacturing;
  RivetLayoutOptions ro;
  ro.thickness = problem.material.thickness;
  ro.diameter = mf.rivet_diameter;
  ro.edge_distance = mf.rivet_edge_distance;
  ro.pitch = mf.rivet_pitch;
  return ro;
}

// Every rivet is given to the mesher as fixed points, so each becomes a node
// (with its footprint ring).
struct RivetPoints {
  std::vector<RivetLayout> layouts;      // per polygon; empty where it is no flange
  std::vector<std::vector<Vec3>> fixed;  // per polygon, m: the flange rivets' points, then self-rivet footprints in tie order
};

RivetPoints lay_out_flange_rivets(const PlateGeometry& geometry, const SheetSpec& sheet, const RivetLayoutOptions& ro) {
  RivetPoints rp;
  rp.fixed.resize(geometry.polygons.size());
  rp.layouts.resize(geometry.polygons.size());
  bool any_flange = false;
  for (size_t k = 0; k < geometry.polygons.size(); ++k) {
    if (geometry.rivet_area[k] < 0) continue;
    any_flange = true;
    rp.layouts[k] = layout_rivets(geometry.polygons[k], geometry.rivet_edge[k], ro, bend_keep_out(geometry, k, sheet));
    rp.fixed[k] = rp.layouts[k].all_points();
  }
  if (!any_flange)
    throw FemError("part", "has no rivet flange: nothing holds it to the structure (a mechanism)");
  return rp;
}

Vec3 plane_normal(const std::vector<Vec3>& poly) {
  Vec3 n = Vec3::Zero();  // Newell
  for (size_t i = 0; i < poly.size(); ++i) n += poly[i].cross(poly[(i + 1) % poly.size()]);
  return Vec3(n.normalized());
}

// Both sheets a self-rivet joins: (polygon, centre on it).
std::array<std::pair<int, Vec3>, 2> tie_sheets(const SelfRivetTie& tie) {
  return {std::pair{tie.polygon_a, tie.point_a}, std::pair{tie.polygon_b, tie.point_b}};
}

// A self-rivet gets a footprint on each sheet, like a flange rivet's (a centre
// and a ring of radius d), so the tie is a small rigid patch whose stiffness
// converges under refinement. A tie between two single nodes is log-singular:
// on slanted's gusset our shells and CalculiX's S4 on the same mesh parted by
// 10 % (docs/fem.md "Self-rivets").
void add_self_rivet_footprints(RivetPoints& rp, const PlateGeometry& geometry, const std::vector<SelfRivetTie>& ties,
                               const RivetLayoutOptions& ro) {
  const double tie_radius = rivet_diameter(ro);
  for (const auto& tie : ties) {
    for (const auto& [k, centre] : tie_sheets(tie)) {
      if (k < 0 || k >= static_cast<int>(geometry.polygons.size()))
        throw FemError("self-rivet", "names polygon " + std::to_string(k) + " of a part with " +
                                         std::to_string(geometry.polygons.size()) + " tabs");
      const auto fp = rivet_footprint(centre, plane_normal(geometry.polygons[k]), tie_radius, ro.footprint_points);
      rp.fixed[k].insert(rp.fixed[k].end(), fp.begin(), fp.end());
    }
  }
}

// Per polygon, the nodes of its elements in first-use order.
std::vector<std::vector<int>> nodes_per_polygon(const PartModel& pm, size_t polygons) {
  const ShellModel& m = pm.model;
  std::vector<std::vector<int>> polygon_nodes(polygons);
  std::vector<std::vector<char>> seen(polygons, std::vector<char>(m.nodes.size(), 0));
  for (size_t e = 0; e < m.triangles.size(); ++e) {
    const int k = pm.mesh.element_polygon[e];
    for (int v : m.triangles[e])
      if (!seen[k][v]) seen[k][v] = 1, polygon_nodes[k].push_back(v);
  }
  return polygon_nodes;
}

// Clamps every rivet's footprint: its centre, its ring and every node of the
// flange inside the ring. The ring alone is not enough: below h ~ d the
// mesher puts lattice nodes inside the ring, and a footprint of seven clamped
// points with free nodes between them softens as h shrinks (hat bracket
// compliance 0.1079 -> 0.1088 J at h = 3 -> 1.5 mm; with the disc clamped
// 0.10787 -> 0.10799 J, docs/fem.md "Riveted multi-leg parts").
void clamp_flange_rivets(PartModel& pm, const PlateGeometry& geometry, const std::vector<RivetLayout>& layouts,
                         const std::vector<std::vector<int>>& polygon_nodes) {
  ShellModel& m = pm.model;
  std::vector<char> clamped(m.nodes.size(), 0);
  auto clamp_once = [&](int v) {
    if (!clamped[v]) clamped[v] = 1, m.clamp(v);
  };
  for (size_t k = 0; k < geometry.polygons.size(); ++k) {
    if (geometry.rivet_area[k] < 0) continue;
    const auto& nodes = pm.mesh.fixed_point_nodes[k];
    const double radius = layouts[k].footprint_radius * (1 + 1e-9) + 1e-12;
    for (size_t r = 0, j = 0; r < layouts[k].footprints.size(); ++r) {
      pm.rivets.push_back(layouts[k].points[r]);
      pm.rivet_polygon.push_back(static_cast<int>(k));
      for (size_t q = 0; q < layouts[k].footprints[r].size(); ++q, ++j) clamp_once(nodes[j]);
      for (int v : polygon_nodes[k])
        if ((m.nodes[v] - layouts[k].points[r]).norm() <= radius) clamp_once(v);
    }
  }
}

// One rigid link per self-rivet from its centre node on sheet a to every other
// node of either sheet inside its footprint (the ring included).
void tie_self_rivets(PartModel& pm, const PlateGeometry& geometry, const std::vector<RivetLayout>& layouts,
                     const std::vector<SelfRivetTie>& ties, const std::vector<std::vector<int>>& polygon_nodes,
                     const RivetLayoutOptions& ro) {
  ShellModel& m = pm.model;
  const int ring_points = ro.footprint_points;
  // Tie footprints were appended after the flange rivets', in tie order, per polygon.
  std::vector<size_t> next(geometry.polygons.size());
  for (size_t k = 0; k < geometry.polygons.size(); ++k)
    next[k] = geometry.rivet_area[k] >= 0 ? layouts[k].all_points().size() : 0;
  const double inside = rivet_diameter(ro) * (1 + 1e-9) + 1e-12;
  for (const auto& tie : ties) {
    const int master = pm.mesh.fixed_point_nodes[tie.polygon_a][next[tie.polygon_a]];
    next[tie.polygon_a] += 1 + ring_points;
    next[tie.polygon_b] += 1 + ring_points;
    std::vector<int> slaves;
    for (const auto& [k, centre] : tie_sheets(tie))
      for (int v : polygon_nodes[k])
        if (v != master && (m.nodes[v] - centre).norm() <= inside && std::find(slaves.begin(), slaves.end(), v) == slaves.end())
          slaves.push_back(v);  // the mesher may have merged coincident points of the two sheets into one node
    if (!slaves.empty()) m.rigid_links.push_back(RigidLink{master, slaves});
  }
}

// The box's cases and mass on its master node (at the box centroid). A case's
// force acts at the centre of mass, so about the master it adds arm x F. A
// load without a mass has no centre of mass of its own: its forces act at the
// centroid (a Load built in code need not set center_of_mass).
void add_load_cases(ShellModel& m, int master, const Load& load) {
  const Vec3 arm = load.mass ? Vec3(load.center_of_mass - load.center) : Vec3::Zero();
  m.add_load(master, load.force, load.moment + arm.cross(load.force));  // the first case: solve()'s
  for (const LoadCase& c : load.cases)
    m.load_cases.push_back(ShellLoadCase{c.name, {NodalLoad{master, c.force, c.moment + arm.cross(c.force)}}});
  if (load.mass) m.point_masses.push_back(PointMass{master, *load.mass, arm, load.inertia});
}

// The load box: rigid, bonded to the base-tab nodes under it (docs/architecture.md "FEM").
void bond_load_box(PartModel& pm, const Load& load, double t) {
  ShellModel& m = pm.model;
  const auto bottom = load.bottom_face();
  const Vec3 down = load.rotation * Vec3(0, 0, -1);
  std::vector<Vec3> footprint;
  for (const Vec3& c : bottom) footprint.push_back(c + 0.5 * t * down);
  const std::vector<int> bonded = nodes_on_polygon(pm.mesh.mesh, footprint, 1e-6 + 1e-6 * t);
  if (bonded.empty())
    throw FemError("load '" + load.name + "'", "no base-tab node lies under the load box: the part is not attached to its load");
  pm.load_node = m.add_node(load.center);
  m.rigid_links.push_back(RigidLink{pm.load_node, bonded});
  add_load_cases(m, pm.load_node, load);
  m.load_node = pm.load_node;
}

}  // namespace

int flange_rivet_count(const Problem& problem, const PlateGeometry& geometry) {
  const RivetPoints rivets = lay_out_flange_rivets(geometry, SheetSpec::from(problem), flange_rivet_options(problem));
  size_t n = 0;
  for (const RivetLayout& layout : rivets.layouts) n += layout.points.size();
  return static_cast<int>(n);
}

PartModel build_part_model(const Problem& problem, int load_index, const PlateGeometry& geometry, const PartModelOptions& options) {
  check_part_model_inputs(problem, load_index, geometry);
  const double t = problem.material.thickness;
  const SheetSpec sheet = SheetSpec::from(problem);
  const RivetLayoutOptions ro = flange_rivet_options(problem);
  RivetPoints rivets = lay_out_flange_rivets(geometry, sheet, ro);
  add_self_rivet_footprints(rivets, geometry, options.self_rivets, ro);

  PartModel pm;
  PlateMeshOptions mo;
  mo.thickness = t;
  mo.element_size = options.element_size;
  pm.mesh = mesh_plates(geometry.polygons, rivets.fixed, mo);
  ShellModel& m = pm.model;
  m.nodes = pm.mesh.mesh.vertices;
  m.triangles = pm.mesh.mesh.triangles;
  m.material = problem.material;

  const std::vector<std::vector<int>> polygon_nodes = nodes_per_polygon(pm, geometry.polygons.size());
  clamp_flange_rivets(pm, geometry, rivets.layouts, polygon_nodes);
  tie_self_rivets(pm, geometry, rivets.layouts, options.self_rivets, polygon_nodes, ro);
  bond_load_box(pm, problem.loads[load_index], t);
  pm.load_index = load_index;
  return pm;
}

ShellSolveOptions part_solve_options(const Problem& problem, const ShellElementOptions& element) {
  ShellSolveOptions so;
  so.element = element;
  so.safety_factor = problem.requirements.safety_factor;
  so.reentrant_corner_clearance = problem.manufacturing.bend_radius;
  return so;
}

StructuralResult analyse_part(const Problem& problem, int load_index, const PlateGeometry& geometry,
                              const PartModelOptions& options, ShellSolver* solver) {
  const auto start = std::chrono::steady_clock::now();
  const PartModel pm = build_part_model(problem, load_index, geometry, options);
  EnvelopeOptions eo;
  const bool eigen = options.eigen_checks;
  eo.buckling = eigen;
  eo.frequencies = eigen ? 3 : 0;
  eo.eigen_only_if_static_passes = true;
  ShellSolver own;
  StructuralResult s;
  s.envelope = analyse_envelope(problem, pm, eo, options.element, solver ? *solver : own);
  const EnvelopeResult& env = s.envelope;
  const CaseResult& stiff = env.cases[env.governing_stiffness];
  const CaseResult& strong = env.cases[env.governing_strength];
  s.compliance = stiff.compliance;
  s.compliance_limit = stiff.compliance_limit;
  s.deflection = stiff.deflection;
  s.deflection_along_force = stiff.deflection_along_force;
  s.max_von_mises = strong.max_von_mises;
  s.margin_of_safety = strong.margin_of_safety;
  s.stiff_enough = std::all_of(env.cases.begin(), env.cases.end(), [](const CaseResult& c) { return c.stiff_enough; });
  s.strong_enough = std::all_of(env.cases.begin(), env.cases.end(), [](const CaseResult& c) { return c.strong_enough; });
  s.stable_enough = env.stable_enough;
  s.frequency_ok = env.frequency_ok;
  s.elements = env.elements;
  s.dofs = env.dofs;
  s.rivets = static_cast<int>(pm.rivets.size());
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

namespace {
// A result's part (or its tabs[]) as JSON; InputError naming `source` when it is not JSON.
nlohmann::json parse_part_json(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source, "", std::string("is not valid JSON (") + e.what() + ")");
  }
}
}  // namespace

PlateGeometry plate_geometry_from_json(const std::string& text, const std::string& source) {
  const nlohmann::json doc = parse_part_json(text, source);
  // Either a part object holding "tabs" (a result's parts[k]) or the bare array.
  const nlohmann::json& tabs_json = doc.is_object() && doc.contains("tabs") ? doc["tabs"] : doc;
  const JsonNode tabs(tabs_json, source, "tabs");
  PlateGeometry g;
  for (size_t i = 0; i < tabs.size(); ++i) {
    const JsonNode tab = tabs.at(i);
    const JsonNode corners = tab.at("corners");
    if (corners.size() < 3) corners.fail("a tab needs at least 3 corners");
    std::vector<Vec3> poly;
    for (size_t k = 0; k < corners.size(); ++k) poly.push_back(corners.at(k).as_vec3());
    g.polygons.push_back(poly);
    const long long ra = tab.has("rivet_area") ? tab.at("rivet_area").as_integer() : -1;
    g.rivet_area.push_back(static_cast<int>(ra));
    g.rivet_edge.push_back(i == 0 ? 0 : kFarEdge);
    // The bend to its parent, as plate_geometry() has it, when the tab carries it.
    int parent = -1;
    double angle = 0;
    if (i > 0 && tab.has("parent") && tab.has("parameters") && !tab.at("parameters").raw().is_null()) {
      const long long pi = tab.at("parent").as_integer();
      if (pi < 0 || pi >= static_cast<long long>(i)) tab.at("parent").fail("must be the index of an earlier tab");
      parent = static_cast<int>(pi);
      angle = std::abs(tab.at("parameters").number_or("theta3", 0.0));
    }
    g.parent.push_back(parent);
    g.bend_angle.push_back(angle);
  }
  return g;
}

std::optional<double> sheet_thickness_from_json(const std::string& text, const std::string& source) {
  const nlohmann::json doc = parse_part_json(text, source);
  if (!doc.is_object() || !doc.contains("thickness_m")) return std::nullopt;
  const nlohmann::json& t = doc["thickness_m"];
  if (!t.is_number() || !(t.get<double>() > 0)) throw InputError(source, "thickness_m", "must be a positive number (m)");
  return t.get<double>();
}

std::vector<SelfRivetTie> self_rivet_ties_from_json(const std::string& text, const std::string& source) {
  const nlohmann::json doc = parse_part_json(text, source);
  std::vector<SelfRivetTie> ties;
  if (!doc.is_object() || !doc.contains("self_rivets")) return ties;
  const long long tab_count = doc.contains("tabs") && doc["tabs"].is_array() ? static_cast<long long>(doc["tabs"].size()) : 0;
  const JsonNode list(doc["self_rivets"], source, "self_rivets");
  for (size_t k = 0; k < list.size(); ++k) {
    const JsonNode entry = list.at(k);
    const JsonNode tabs = entry.at("tabs");
    if (tabs.size() != 2) tabs.fail("needs the two tied tabs' indices");
    const JsonNode points = entry.at("points");
    if (points.size() != 2) points.fail("needs one point on each tied tab (m)");
    SelfRivetTie tie;
    for (int s = 0; s < 2; ++s) {
      const long long i = tabs.at(s).as_integer();
      if (i < 0 || i >= tab_count) tabs.at(s).fail("is not a tab index of this part (it has " + std::to_string(tab_count) + " tabs)");
      (s == 0 ? tie.polygon_a : tie.polygon_b) = static_cast<int>(i);
    }
    tie.point_a = points.at(0).as_vec3();
    tie.point_b = points.at(1).as_vec3();
    ties.push_back(tie);
  }
  return ties;
}

}  // namespace sheetgen
