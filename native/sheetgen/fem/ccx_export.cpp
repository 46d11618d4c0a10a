#include "sheetgen/fem/ccx_export.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <unordered_map>

#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

// Does the master of a rigid link carry elements? Then it cannot be the REF
// NODE (ccx expands shell nodes), and a separate ref node is written.
std::vector<char> element_nodes(const ShellModel& m) {
  std::vector<char> used(m.nodes.size(), 0);
  for (const auto& t : m.triangles)
    for (int k : t) used[k] = 1;
  return used;
}

using Quad = std::array<int, 4>;  // deck node ids, counter-clockwise

// The deck's nodes as they are written, and which split nodes are held.
struct Deck {
  explicit Deck(std::ostream& o) : out(o) {}
  std::ostream& out;
  CcxDeckMap map;
  int next = 0;                                                 // the last deck node id
  std::vector<Vec3> position = std::vector<Vec3>(1, Vec3::Zero());  // by deck id (ids are consecutive from 1)
  std::vector<int> held_clamped;                                // deck ids of split nodes to clamp
  std::vector<std::vector<int>> held_linked;                    // per link, deck ids of split nodes in it

  void node(int id, const Vec3& p) {
    out << id << ", " << p.x() << ", " << p.y() << ", " << p.z() << "\n";
    position.push_back(p);
  }
};

// How each model node is held: clamped in all six DOFs, or in a rigid link.
struct ModelHolds {
  std::vector<char> in_element;  // #N
  std::vector<char> clamped;     // #N
  std::vector<int> link_of;      // #N, the rigid link a node is master or slave of, -1 if none
};

ModelHolds model_holds(const ShellModel& m) {
  ModelHolds h;
  h.in_element = element_nodes(m);
  h.clamped.assign(m.nodes.size(), 0);
  std::vector<std::array<bool, 6>> fixed(m.nodes.size(), std::array<bool, 6>{});
  for (const NodeSupport& s : m.supports)
    for (int d = 0; d < 6; ++d) fixed[s.node][d] = fixed[s.node][d] || s.fixed[d];
  for (size_t i = 0; i < m.nodes.size(); ++i)
    h.clamped[i] = std::all_of(fixed[i].begin(), fixed[i].end(), [](bool b) { return b; });
  h.link_of.assign(m.nodes.size(), -1);
  for (size_t l = 0; l < m.rigid_links.size(); ++l) {
    h.link_of[m.rigid_links[l].master] = static_cast<int>(l);
    for (int s : m.rigid_links[l].slaves) h.link_of[s] = static_cast<int>(l);
  }
  return h;
}

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void check_export_options(const ShellModel& m, const CcxExportOptions& options) {
  if (options.element_type != "S4" && options.element_type != "S4R" && options.element_type != "S8R" &&
      options.element_type != "S6")
    throw FemError("ccx export options.element_type", "must be S4, S4R, S6 or S8R (got " + options.element_type + ")");
  const std::vector<ShellLoadCase> cases = m.cases();
  const std::string field = "ccx export options.";
  if (options.buckle_case < -1 || options.buckle_case >= static_cast<int>(cases.size()))
    throw FemError(field + "buckle_case", "must be -1 or a case index below " + std::to_string(cases.size()) +
                                              " (got " + std::to_string(options.buckle_case) + ")");
  if (options.buckle_case >= 0) {
    if (options.buckling_factors < 1)
      throw FemError(field + "buckling_factors", "must be >= 1 (got " + std::to_string(options.buckling_factors) + ")");
    const ShellLoadCase& c = cases[options.buckle_case];
    // ccx would scale a zero load without end; a factor of it means nothing.
    if (std::none_of(c.loads.begin(), c.loads.end(),
                     [](const NodalLoad& f) { return f.force.squaredNorm() > 0 || f.moment.squaredNorm() > 0; }))
      throw FemError(field + "buckle_case", "names case '" + c.name + "', which has no non-zero load");
  }
  if (options.frequency_modes < 0)
    throw FemError(field + "frequency_modes", "must be >= 0 (got " + std::to_string(options.frequency_modes) + ")");
  if (options.frequency_modes > 0 && !(std::isfinite(m.material.density) && m.material.density > 0))
    throw FemError("material.density", "must be a finite number > 0 kg/m^3 for *FREQUENCY (got " +
                                           str(m.material.density) + ")");
  // Before a line is written: a deck is never left half-written.
  for (size_t i = 0; options.frequency_modes > 0 && i < m.point_masses.size(); ++i) {
    const int node = m.point_masses[i].node;
    const bool linked = std::any_of(m.rigid_links.begin(), m.rigid_links.end(), [node](const RigidLink& l) {
      return l.master == node || std::find(l.slaves.begin(), l.slaves.end(), node) != l.slaves.end();
    });
    // ccx builds a rigid body from its nodes' translations alone, so a body
    // on one shell node would leave the mass's rotation free.
    if (!linked)
      throw FemError("point_masses[" + std::to_string(i) + "]",
                     "sits on node " + std::to_string(node) +
                         ", which is in no rigid link; the CalculiX deck ties a rigid mass to a link's REF NODE");
    try {
      lumped_rigid_mass(m.point_masses[i], m.nodes[m.point_masses[i].node]);
    } catch (const FemError& e) {
      throw FemError("point_masses[" + std::to_string(i) + "]", e.problem());
    }
  }
}

// Numbers the model nodes that elements or rigid links use, from 1, and writes them.
void write_model_nodes(const ShellModel& m, const ModelHolds& h, const CcxExportOptions& options, Deck& d) {
  d.map.node_id.assign(m.nodes.size(), -1);
  std::vector<char> written(m.nodes.size(), 0);
  for (size_t i = 0; i < m.nodes.size(); ++i) written[i] = h.in_element[i];
  for (const RigidLink& l : m.rigid_links) {
    written[l.master] = 1;
    for (int s : l.slaves) written[s] = 1;
  }
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (written[i]) d.map.node_id[i] = ++d.next;

  // CalculiX reads a number from at most 20 characters: 13 significant digits
  // keep "-1.234567890123E-05" (19) inside that; more digits fail as "error reading *NODE".
  d.out << std::setprecision(13);
  d.out << "*HEADING\n" << options.heading << "\n** Units: m, N, Pa. Written by sheetgen (docs/fem.md).\n";
  d.out << "*NODE, NSET=NALL\n";
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (written[i]) d.node(d.map.node_id[i], m.nodes[i]);
}

// The split adds nodes our model does not have. Where our element's field is
// set by its corner values alone, a new node must be held the same way, or
// the deck is a softer model than ours: an edge whose two ends are clamped
// does not move (DKT's w is Hermite in the end values and tangential slopes,
// its normal slope and OPT's membrane field interpolate the end values and
// drilling rotations), and an edge or triangle whose corners all follow one
// rigid link moves rigidly (both elements reproduce rigid motions exactly).
// So a midpoint or centroid is clamped, or joins the link, when all its
// corners are. Without this a rivet footprint in ccx was seven clamped points
// with free midpoints between them (docs/fem.md "Riveted multi-leg parts").
void hold_split_node(const ModelHolds& h, int id, std::initializer_list<int> corners, Deck& d) {
  const int first = *corners.begin();
  bool all_clamped = true, one_link = h.link_of[first] >= 0;
  for (int c : corners) {
    all_clamped = all_clamped && h.clamped[c];
    one_link = one_link && h.link_of[c] == h.link_of[first];
  }
  if (all_clamped) d.held_clamped.push_back(id);
  else if (one_link) d.held_linked[h.link_of[first]].push_back(id);
}

// The midpoint of a model edge as a deck node, written once and shared by the
// two triangles of the edge (so the deck's mesh is conforming), held like its ends.
class EdgeMidpoints {
 public:
  EdgeMidpoints(const ShellModel& m, const ModelHolds& h, Deck& d) : m_(m), h_(h), d_(d) {}
  int operator()(int a, int b) {
    const long long key = static_cast<long long>(std::min(a, b)) * static_cast<long long>(m_.nodes.size()) + std::max(a, b);
    auto it = id_.find(key);
    if (it != id_.end()) return it->second;
    const int id = ++d_.next;
    d_.node(id, 0.5 * (m_.nodes[a] + m_.nodes[b]));
    id_.emplace(key, id);
    hold_split_node(h_, id, {a, b}, d_);
    return id;
  }

 private:
  const ShellModel& m_;
  const ModelHolds& h_;
  Deck& d_;
  std::unordered_map<long long, int> id_;
};

// Splits every triangle into three quads through its edge midpoints (shared
// between neighbours) and its centroid, writing the new nodes.
std::vector<Quad> split_into_quads(const ShellModel& m, const ModelHolds& h, Deck& d) {
  EdgeMidpoints mid(m, h, d);
  std::vector<Quad> quads;
  quads.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles) {
    const int m01 = mid(t[0], t[1]), m12 = mid(t[1], t[2]), m20 = mid(t[2], t[0]);
    const Vec3 c = (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]]) / 3.0;
    const int cid = ++d.next;
    d.node(cid, c);
    hold_split_node(h, cid, {t[0], t[1], t[2]}, d);
    // Counter-clockwise like the triangle, so every quad keeps its normal.
    const std::vector<int>& id = d.map.node_id;
    quads.push_back({id[t[0]], m01, cid, m20});
    quads.push_back({id[t[1]], m12, cid, m01});
    quads.push_back({id[t[2]], m20, cid, m12});
  }
  return quads;
}

// S6: our triangles themselves, quadratic, with a node at each edge midpoint
// (CalculiX's order: the three corners, then the sides 12, 23, 31).
std::vector<std::vector<int>> quadratic_triangles(const ShellModel& m, const ModelHolds& h, Deck& d) {
  EdgeMidpoints mid(m, h, d);
  std::vector<std::vector<int>> elements;
  elements.reserve(m.triangles.size());
  const std::vector<int>& id = d.map.node_id;
  for (const auto& t : m.triangles)
    elements.push_back({id[t[0]], id[t[1]], id[t[2]], mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0])});
  return elements;
}

// S8R: a mid-side node on every quad edge, held like the split nodes (clamped
// when both ends are, in a rigid body when both ends are in it). Per quad, the
// side nodes of its edges 01, 12, 23, 30.
std::vector<Quad> add_side_nodes(const ShellModel& m, const ModelHolds& h, const std::vector<Quad>& quads, Deck& d) {
  std::vector<char> deck_clamped(d.next + 1, 0);
  std::vector<int> deck_link(d.next + 1, -1);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (d.map.node_id[i] > 0) {
      deck_clamped[d.map.node_id[i]] = h.clamped[i];
      deck_link[d.map.node_id[i]] = h.link_of[i];
    }
  for (int id : d.held_clamped) deck_clamped[id] = 1;
  for (size_t l = 0; l < d.held_linked.size(); ++l)
    for (int id : d.held_linked[l]) deck_link[id] = static_cast<int>(l);
  std::unordered_map<long long, int> side_node;
  const long long stride = d.next + 1LL;  // corner ids are below it
  auto side = [&](int a, int b) {
    const long long key = static_cast<long long>(std::min(a, b)) * stride + std::max(a, b);
    auto it = side_node.find(key);
    if (it != side_node.end()) return it->second;
    const int id = ++d.next;
    d.node(id, 0.5 * (d.position[a] + d.position[b]));
    side_node.emplace(key, id);
    if (deck_clamped[a] && deck_clamped[b]) d.held_clamped.push_back(id);
    else if (deck_link[a] >= 0 && deck_link[a] == deck_link[b]) d.held_linked[deck_link[a]].push_back(id);
    return id;
  };
  std::vector<Quad> sides;
  for (const auto& q : quads) sides.push_back({side(q[0], q[1]), side(q[1], q[2]), side(q[2], q[3]), side(q[3], q[0])});
  return sides;
}

// The deck's elements as lists of deck node ids, writing the nodes they add.
std::vector<std::vector<int>> deck_elements(const ShellModel& m, const ModelHolds& h, const std::string& type, Deck& d) {
  if (type == "S6") return quadratic_triangles(m, h, d);
  const std::vector<Quad> quads = split_into_quads(m, h, d);
  const std::vector<Quad> sides = type == "S8R" ? add_side_nodes(m, h, quads, d) : std::vector<Quad>{};
  std::vector<std::vector<int>> elements;
  elements.reserve(quads.size());
  for (size_t k = 0; k < quads.size(); ++k) {
    elements.emplace_back(quads[k].begin(), quads[k].end());
    if (!sides.empty()) elements.back().insert(elements.back().end(), sides[k].begin(), sides[k].end());
  }
  return elements;
}

// Quadratic shells (S6, S8R) get each element's own flat normal at every node
// (*NORMAL). Otherwise ccx averages, per node, the normals of the elements
// within 20 deg of each other and offsets the expanded solid's faces by t/2
// along that average. Our bend facets are just under 20 deg, so at a fold the
// faces move sideways by up to t/2 tan(10 deg) = 0.14 mm at t = 1.6 mm, more
// than the small quads split from a triangle there are wide, and ccx stops on
// a nonpositive jacobian. Given normals are grouped only within 0.5 deg, so
// ccx expands each side of a fold on its own and ties the two rigidly, which
// is how our flat elements meet there too.
// Per triangle of the model: elements k (S6) or 3k..3k+2 (S8R, the split).
void write_facet_normals(const ShellModel& m, const std::vector<std::vector<int>>& elements, const std::string& type,
                         std::ostream& out) {
  if (type != "S6" && type != "S8R") return;
  const size_t per_triangle = type == "S6" ? 1 : 3;
  out << "*NORMAL\n";
  for (size_t k = 0; k < elements.size(); ++k) {
    const auto& t = m.triangles[k / per_triangle];
    const Vec3 n = (m.nodes[t[1]] - m.nodes[t[0]]).cross(m.nodes[t[2]] - m.nodes[t[0]]).normalized();
    for (int id : elements[k]) out << k + 1 << ", " << id << ", " << n.x() << ", " << n.y() << ", " << n.z() << "\n";
  }
}

// Rigid-link reference and rotation nodes.
void write_link_nodes(const ShellModel& m, const ModelHolds& h, Deck& d) {
  for (const RigidLink& l : m.rigid_links) {
    const Vec3& p = m.nodes[l.master];
    int ref = d.map.node_id[l.master];
    if (h.in_element[l.master]) {
      ref = ++d.next;
      d.out << ref << ", " << p.x() << ", " << p.y() << ", " << p.z() << "\n";
    }
    const int rot = ++d.next;
    d.out << rot << ", " << p.x() << ", " << p.y() << ", " << p.z() << "\n";
    d.map.ref_node.push_back(ref);
    d.map.rot_node.push_back(rot);
  }
}

// A point mass in the deck: MASS elements on points of their own, tied by a
// *RIGID BODY of their own to the REF/ROT NODE of the link the mass's node
// follows (its master or a slave; check_export_options makes sure there is
// one). The separate set keeps the link's RIGIDi set the model's link alone.
struct MassBody {
  int ref = -1, rot = -1;          // deck ids of the REF and ROT NODE
  std::vector<int> point_node;     // deck ids of the mass points
  std::vector<double> point_mass;  // kg, per point
};

std::vector<MassBody> write_mass_nodes(const ShellModel& m, const ModelHolds& h, Deck& d) {
  std::vector<MassBody> bodies;
  for (const PointMass& p : m.point_masses) {
    MassBody b;
    const int link = h.link_of[p.node];
    b.ref = d.map.ref_node[link];
    b.rot = d.map.rot_node[link];
    for (const CcxLumpedMass& q : lumped_rigid_mass(p, m.nodes[p.node])) {
      const int id = ++d.next;
      d.out << id << ", " << q.position.x() << ", " << q.position.y() << ", " << q.position.z() << "\n";
      b.point_node.push_back(id);
      b.point_mass.push_back(q.mass);
    }
    d.map.mass_ref_node.push_back(b.ref);
    bodies.push_back(std::move(b));
  }
  return bodies;
}

// Elements, material, section and rigid bodies.
void write_elements(const ShellModel& m, const ModelHolds& h, const std::vector<std::vector<int>>& elements,
                    const std::string& element_type, Deck& d) {
  std::ostream& out = d.out;
  out << "*ELEMENT, TYPE=" << element_type << ", ELSET=EALL\n";
  int eid = 0;
  for (const std::vector<int>& e : elements) {
    out << ++eid;
    for (int id : e) out << ", " << id;
    out << "\n";
  }
  d.map.element_count = eid;
  write_facet_normals(m, elements, element_type, out);
  out << "*MATERIAL, NAME=SHEET\n*ELASTIC\n"
      << m.material.youngs_modulus << ", " << m.material.poisson_ratio << "\n";
  if (std::isfinite(m.material.density) && m.material.density > 0)
    out << "*DENSITY\n" << m.material.density << "\n";  // kg/m^3: with m, N, Pa the frequencies come out in Hz
  out << "*SHELL SECTION, ELSET=EALL, MATERIAL=SHEET\n" << m.material.thickness << "\n";
  for (size_t l = 0; l < m.rigid_links.size(); ++l) {
    const RigidLink& link = m.rigid_links[l];
    out << "*NSET, NSET=RIGID" << l + 1 << "\n";
    if (h.in_element[link.master]) out << d.map.node_id[link.master] << ",\n";
    for (int s : link.slaves) out << d.map.node_id[s] << ",\n";
    for (int id : d.held_linked[l]) out << id << ",\n";
    out << "*RIGID BODY, NSET=RIGID" << l + 1 << ", REF NODE=" << d.map.ref_node[l] << ", ROT NODE=" << d.map.rot_node[l]
        << "\n";
  }
}

// MASS elements (one ELSET per distinct mass: *MASS takes one value per set)
// and the rigid body of each point mass.
void write_mass_bodies(const std::vector<MassBody>& bodies, Deck& d) {
  std::ostream& out = d.out;
  int eid = d.map.element_count;
  for (size_t k = 0; k < bodies.size(); ++k) {
    const MassBody& b = bodies[k];
    std::vector<std::pair<double, std::vector<int>>> groups;
    for (size_t j = 0; j < b.point_node.size(); ++j) {
      auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& x) { return x.first == b.point_mass[j]; });
      if (g == groups.end()) g = groups.insert(groups.end(), {b.point_mass[j], {}});
      g->second.push_back(b.point_node[j]);
    }
    for (size_t g = 0; g < groups.size(); ++g) {
      const std::string elset = "EMASS" + std::to_string(k + 1) + "_" + std::to_string(g + 1);
      out << "*ELEMENT, TYPE=MASS, ELSET=" << elset << "\n";
      for (int id : groups[g].second) out << ++eid << ", " << id << "\n";
      out << "*MASS, ELSET=" << elset << "\n" << groups[g].first << "\n";
    }
    out << "*NSET, NSET=MASS" << k + 1 << "\n";
    for (int id : b.point_node) out << id << ",\n";
    out << "*RIGID BODY, NSET=MASS" << k + 1 << ", REF NODE=" << b.ref << ", ROT NODE=" << b.rot << "\n";
  }
  d.map.mass_element_count = eid - d.map.element_count;
}

// Where a model DOF lives in the deck: (deck node id, ccx DOF 1..6). A DOF of
// an element-free master lives on its ref node (translations) or rot node
// (rotations, as translations 1-3).
class DofTarget {
 public:
  DofTarget(const ShellModel& m, const ModelHolds& h, const CcxDeckMap& map) : map_(map), master_link_(m.nodes.size(), -1) {
    for (size_t l = 0; l < m.rigid_links.size(); ++l)
      if (!h.in_element[m.rigid_links[l].master]) master_link_[m.rigid_links[l].master] = static_cast<int>(l);
  }
  std::pair<int, int> operator()(int node, int dof) const {
    const int l = master_link_[node];
    if (l < 0) return std::make_pair(map_.node_id[node], dof + 1);
    return dof < 3 ? std::make_pair(map_.ref_node[l], dof + 1) : std::make_pair(map_.rot_node[l], dof - 2);
  }

 private:
  const CcxDeckMap& map_;
  std::vector<int> master_link_;
};

// Supports and held split nodes, in the model section: they hold in every step.
void write_boundary(const ShellModel& m, const DofTarget& target, const Deck& d) {
  d.out << "*BOUNDARY\n";
  for (const NodeSupport& s : m.supports)
    for (int k = 0; k < 6; ++k)
      if (s.fixed[k]) {
        const auto [id, dof] = target(s.node, k);
        d.out << id << ", " << dof << ", " << dof << "\n";
      }
  for (int id : d.held_clamped) d.out << id << ", 1, 6\n";
}

// ccx keeps the concentrated loads of a step in the next ones unless OP=NEW
// drops them; the deck's first step has none to drop (and stays "*CLOAD", as
// the deck's readers in tools/ expect).
void write_cloads(const std::vector<NodalLoad>& loads, const DofTarget& target, bool first_step, std::ostream& out) {
  out << (first_step ? "*CLOAD\n" : "*CLOAD, OP=NEW\n");
  for (const NodalLoad& f : loads)
    for (int k = 0; k < 6; ++k) {
      const double v = k < 3 ? f.force(k) : f.moment(k - 3);
      if (v == 0) continue;
      const auto [id, dof] = target(f.node, k);
      out << id << ", " << dof << ", " << v << "\n";
    }
}

// A case name inside a "**" comment line: one line, whatever it holds.
std::string comment_text(std::string name) {
  for (char& c : name)
    if (c == '\n' || c == '\r') c = ' ';
  return name;
}

// The eigenvalue steps come first, so that the last step of the deck is a
// static case: readers that take the .dat's last displacement or stress block
// (tools/sheetgen_tools/ccx_check.py) still see a static solution. *NODE FILE
// writes the mode shapes to the .frd for viewing (cgx); the request carries
// over to the static steps after them.
void write_steps(const ShellModel& m, const DofTarget& target, const CcxExportOptions& options, Deck& d) {
  std::ostream& out = d.out;
  const std::vector<ShellLoadCase> cases = m.cases();
  bool first = true;
  if (options.buckle_case >= 0) {
    const ShellLoadCase& c = cases[options.buckle_case];
    // Not a PERTURBATION step: no preload, the factors multiply this step's loads alone.
    out << "** Linear buckling of load case " << options.buckle_case + 1 << " '" << comment_text(c.name)
        << "': each factor multiplies the loads of this step\n*STEP\n*BUCKLE\n" << options.buckling_factors << "\n";
    write_cloads(c.loads, target, first, out);
    out << "*NODE FILE\nU\n*END STEP\n";
    first = false;
  }
  if (options.frequency_modes > 0) {
    out << "** Natural frequencies (Hz): the sheet's *DENSITY and the MASS elements\n*STEP\n*FREQUENCY\n"
        << options.frequency_modes << "\n*NODE FILE\nU\n*END STEP\n";
    first = false;
  }
  for (size_t c = 0; c < cases.size(); ++c) {
    out << "** Load case " << c + 1 << " '" << comment_text(cases[c].name) << "'\n*STEP\n*STATIC\n";
    write_cloads(cases[c].loads, target, first, out);
    out << "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
    first = false;
  }
  d.map.static_steps = static_cast<int>(cases.size());
}

}  // namespace

std::vector<CcxLumpedMass> lumped_rigid_mass(const PointMass& body, const Vec3& node_position) {
  if (!std::isfinite(body.mass) || !(body.mass > 0))
    throw FemError("point mass", "mass must be a finite number > 0 kg (got " + str(body.mass) + ")");
  const Vec3 c = node_position + body.offset;
  const Eigen::Matrix3d J = 0.5 * (body.inertia + body.inertia.transpose());
  // J = tr(S) I - S for the second moment S = sum m_i r_i r_i^T about the
  // centre, so S = tr(J)/2 I - J; m/6 at +-a_k q_k adds 2 (m/6) a_k^2 = s_k on q_k.
  const Eigen::Matrix3d S = 0.5 * J.trace() * Eigen::Matrix3d::Identity() - J;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
  const double scale = std::abs(J.trace());
  if (eig.eigenvalues().minCoeff() < -1e-9 * scale) {
    const Vec3 principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J).eigenvalues();
    throw FemError("point mass", "inertia breaks the triangle inequality J1 <= J2 + J3 (principal moments " +
                                     str(principal(0)) + ", " + str(principal(1)) + ", " + str(principal(2)) +
                                     " kg m^2), which no body has");
  }
  std::vector<CcxLumpedMass> points;
  const double sixth = body.mass / 6;
  int axes = 0;
  for (int k = 0; k < 3; ++k) {
    const double s = eig.eigenvalues()(k);
    if (s <= 1e-12 * scale) continue;  // a flat or line body: no extent along q_k
    const Vec3 a = std::sqrt(3 * s / body.mass) * eig.eigenvectors().col(k);
    points.push_back({c + a, sixth});
    points.push_back({c - a, sixth});
    ++axes;
  }
  if (axes < 3) points.push_back({c, (3 - axes) * body.mass / 3});
  return points;
}

int find_load_case(const ShellModel& m, const std::string& name) {
  const std::vector<ShellLoadCase> cases = m.cases();
  for (size_t i = 0; i < cases.size(); ++i)
    if (cases[i].name == name) return static_cast<int>(i);
  if (!name.empty() && name.find_first_not_of("0123456789") == std::string::npos && name.size() < 9) {
    const int index = std::stoi(name);
    if (index < static_cast<int>(cases.size())) return index;
  }
  std::string names;
  for (const ShellLoadCase& c : cases) names += (names.empty() ? "'" : ", '") + c.name + "'";
  throw FemError("load case", "no case is named '" + name + "' and it is no index below " +
                                  std::to_string(cases.size()) + " (the cases: " + names + ")");
}

CcxDeckMap write_ccx_deck(const ShellModel& m, std::ostream& out, const CcxExportOptions& options) {
  validate_shell_model(m);
  check_export_options(m, options);
  const ModelHolds h = model_holds(m);
  Deck d(out);
  d.held_linked.resize(m.rigid_links.size());
  write_model_nodes(m, h, options, d);
  const std::vector<std::vector<int>> elements = deck_elements(m, h, options.element_type, d);
  write_link_nodes(m, h, d);
  // The masses matter to the frequency step alone; a static deck stays without them.
  std::vector<MassBody> bodies;
  if (options.frequency_modes > 0) bodies = write_mass_nodes(m, h, d);
  d.map.node_count = d.next;
  write_elements(m, h, elements, options.element_type, d);
  write_mass_bodies(bodies, d);
  const DofTarget target(m, h, d.map);
  write_boundary(m, target, d);
  write_steps(m, target, options, d);
  return d.map;
}

CcxDeckMap write_ccx_deck(const ShellModel& model, const std::string& path, const CcxExportOptions& options) {
  std::ofstream f(path);
  if (!f) throw FemError("ccx export", "cannot write " + path);
  const CcxDeckMap map = write_ccx_deck(model, f, options);
  f.close();
  if (!f) throw FemError("ccx export", "writing " + path + " failed");
  return map;
}

}  // namespace sheetgen
