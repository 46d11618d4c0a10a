#include "sheetgen/fem/ccx_export.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
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

void check_export_options(const CcxExportOptions& options) {
  if (options.element_type != "S4" && options.element_type != "S4R" && options.element_type != "S8R")
    throw FemError("ccx export", "element type must be S4, S4R or S8R (got " + options.element_type + ")");
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

// Splits every triangle into three quads through its edge midpoints (shared
// between neighbours) and its centroid, writing the new nodes.
std::vector<Quad> split_into_quads(const ShellModel& m, const ModelHolds& h, Deck& d) {
  std::unordered_map<long long, int> midpoint;
  auto mid = [&](int a, int b) {
    const long long key = static_cast<long long>(std::min(a, b)) * static_cast<long long>(m.nodes.size()) + std::max(a, b);
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    const Vec3 p = 0.5 * (m.nodes[a] + m.nodes[b]);
    const int id = ++d.next;
    d.node(id, p);
    midpoint.emplace(key, id);
    hold_split_node(h, id, {a, b}, d);
    return id;
  };
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
  d.map.node_count = d.next;
}

// Elements, material, section and rigid bodies.
void write_elements(const ShellModel& m, const ModelHolds& h, const std::vector<Quad>& quads, const std::vector<Quad>& sides,
                    const std::string& element_type, Deck& d) {
  std::ostream& out = d.out;
  out << "*ELEMENT, TYPE=" << element_type << ", ELSET=EALL\n";
  int eid = 0;
  for (size_t k = 0; k < quads.size(); ++k) {
    const auto& q = quads[k];
    out << ++eid << ", " << q[0] << ", " << q[1] << ", " << q[2] << ", " << q[3];
    if (!sides.empty()) out << ", " << sides[k][0] << ", " << sides[k][1] << ", " << sides[k][2] << ", " << sides[k][3];
    out << "\n";
  }
  d.map.element_count = eid;
  out << "*MATERIAL, NAME=SHEET\n*ELASTIC\n"
      << m.material.youngs_modulus << ", " << m.material.poisson_ratio << "\n";
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

// The static step: supports, held split nodes and loads.
void write_step(const ShellModel& m, const ModelHolds& h, const Deck& d) {
  std::ostream& out = d.out;
  const DofTarget dof_target(m, h, d.map);
  out << "*STEP\n*STATIC\n";
  out << "*BOUNDARY\n";
  for (const NodeSupport& s : m.supports)
    for (int k = 0; k < 6; ++k)
      if (s.fixed[k]) {
        const auto [id, dof] = dof_target(s.node, k);
        out << id << ", " << dof << ", " << dof << "\n";
      }
  for (int id : d.held_clamped) out << id << ", 1, 6\n";
  out << "*CLOAD\n";
  for (const NodalLoad& f : m.loads)
    for (int k = 0; k < 6; ++k) {
      const double v = k < 3 ? f.force(k) : f.moment(k - 3);
      if (v == 0) continue;
      const auto [id, dof] = dof_target(f.node, k);
      out << id << ", " << dof << ", " << v << "\n";
    }
  out << "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
}

}  // namespace

CcxDeckMap write_ccx_deck(const ShellModel& m, std::ostream& out, const CcxExportOptions& options) {
  validate_shell_model(m);
  check_export_options(options);
  const ModelHolds h = model_holds(m);
  Deck d(out);
  d.held_linked.resize(m.rigid_links.size());
  write_model_nodes(m, h, options, d);
  const std::vector<Quad> quads = split_into_quads(m, h, d);
  const std::vector<Quad> sides = options.element_type == "S8R" ? add_side_nodes(m, h, quads, d) : std::vector<Quad>{};
  write_link_nodes(m, h, d);
  write_elements(m, h, quads, sides, options.element_type, d);
  write_step(m, h, d);
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

std::map<int, Vec3> read_ccx_displacements(const std::string& dat_path) {
  std::ifstream f(dat_path);
  if (!f) throw FemError("ccx results", "cannot read " + dat_path);
  std::map<int, Vec3> block, last;
  bool in_block = false, found = false;
  std::string line;
  while (std::getline(f, line)) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      in_block = true;
      found = true;
      block.clear();
      continue;
    }
    if (!in_block) continue;
    std::istringstream s(line);
    int id;
    double x, y, z;
    if (s >> id >> x >> y >> z) {
      block[id] = Vec3(x, y, z);
    } else if (!block.empty() && line.find_first_not_of(" \t\r") != std::string::npos) {
      in_block = false;  // the next block's header
      last = block;
    }
  }
  if (in_block) last = block;
  if (!found || last.empty()) throw FemError("ccx results", dat_path + " holds no displacement block");
  return last;
}

CcxSolution solve_with_ccx(const ShellModel& m, const std::string& work_dir, const std::string& job,
                           const std::string& ccx, const CcxExportOptions& options) {
  const std::string inp = work_dir + "/" + job + ".inp";
  const CcxDeckMap map = write_ccx_deck(m, inp, options);
  std::remove((work_dir + "/" + job + ".dat").c_str());
  const std::string cmd = "cd '" + work_dir + "' && '" + ccx + "' -i '" + job + "' > '" + job + ".log' 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  CcxSolution sol;
  sol.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream log(work_dir + "/" + job + ".log");
  std::stringstream log_text;
  log_text << log.rdbuf();
  if (rc != 0 || log_text.str().find("*ERROR") != std::string::npos) {
    std::string tail = log_text.str();
    if (tail.size() > 400) tail = tail.substr(tail.size() - 400);
    throw FemError("ccx", "`" + cmd + "` failed (status " + std::to_string(rc) + "): " + tail);
  }
  const std::map<int, Vec3> u = read_ccx_displacements(work_dir + "/" + job + ".dat");
  auto at = [&u](int id) {
    auto it = u.find(id);
    return it == u.end() ? Vec3(Vec3::Zero()) : it->second;
  };
  sol.displacements.assign(m.nodes.size(), Vector6d::Zero());
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (map.node_id[i] > 0) sol.displacements[i].head<3>() = at(map.node_id[i]);
  std::vector<char> has_rotation(m.nodes.size(), 0);
  for (size_t l = 0; l < m.rigid_links.size(); ++l) {
    const int master = m.rigid_links[l].master;
    sol.displacements[master].head<3>() = at(map.ref_node[l]);
    sol.displacements[master].tail<3>() = at(map.rot_node[l]);
    has_rotation[master] = 1;
  }
  int load_node = m.load_node;
  double best = -1;
  for (const NodalLoad& f : m.loads) {
    sol.compliance += f.force.dot(sol.displacements[f.node].head<3>());
    if (f.moment.squaredNorm() > 0) {
      if (has_rotation[f.node]) sol.compliance += f.moment.dot(sol.displacements[f.node].tail<3>());
      else sol.compliance_complete = false;
    }
    if (m.load_node < 0 && sol.displacements[f.node].head<3>().norm() > best) {
      best = sol.displacements[f.node].head<3>().norm();
      load_node = f.node;
    }
  }
  if (load_node >= 0) sol.load_deflection = sol.displacements[load_node].head<3>().norm();
  return sol;
}

}  // namespace sheetgen
