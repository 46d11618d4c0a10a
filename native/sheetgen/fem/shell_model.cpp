#include "sheetgen/fem/shell_model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/shell_solver_impl.hpp"

namespace sheetgen {

// ---------------------------------------------------------------- ShellModel

int ShellModel::add_node(const Vec3& p) {
  nodes.push_back(p);
  return static_cast<int>(nodes.size()) - 1;
}

void ShellModel::clamp(int node) {
  NodeSupport s;
  s.node = node;
  supports.push_back(s);
}

void ShellModel::add_load(int node, const Vec3& force, const Vec3& moment) {
  loads.push_back(NodalLoad{node, force, moment});
}

std::vector<ShellLoadCase> ShellModel::cases() const {
  if (!load_cases.empty()) return load_cases;
  return {ShellLoadCase{"design", loads}};
}

void ShellModel::add_surface_traction(const Vec3& traction, const std::vector<int>& elements) {
  std::vector<Vec3> share(nodes.size(), Vec3::Zero());
  auto lump = [&](int e) {
    const auto& t = triangles.at(static_cast<size_t>(e));
    const double area = 0.5 * (nodes[t[1]] - nodes[t[0]]).cross(nodes[t[2]] - nodes[t[0]]).norm();
    for (int k = 0; k < 3; ++k) share[t[k]] += traction * (area / 3.0);
  };
  if (elements.empty()) {
    for (int e = 0; e < static_cast<int>(triangles.size()); ++e) lump(e);
  } else {
    for (int e : elements) lump(e);
  }
  for (int n = 0; n < static_cast<int>(nodes.size()); ++n)
    if (share[n].squaredNorm() > 0) add_load(n, share[n]);
}

// ---------------------------------------------------------------- validation

namespace {

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

void check_node(const ShellModel& m, int node, const std::string& what) {
  if (node < 0 || node >= static_cast<int>(m.nodes.size()))
    throw FemError(what, "node index " + std::to_string(node) + " is out of range [0, " +
                             std::to_string(m.nodes.size()) + ")");
}

void check_material(const Material& mat) {
  if (!(std::isfinite(mat.thickness) && mat.thickness > 0))
    throw FemError("material.thickness", "must be a finite number > 0 m (got " + str(mat.thickness) + ")");
  if (!(std::isfinite(mat.youngs_modulus) && mat.youngs_modulus > 0))
    throw FemError("material.youngs_modulus", "must be a finite number > 0 Pa (got " + str(mat.youngs_modulus) + ")");
  if (!(std::isfinite(mat.poisson_ratio) && mat.poisson_ratio > -1.0 && mat.poisson_ratio < 0.5))
    throw FemError("material.poisson_ratio", "must lie in (-1, 0.5) (got " + str(mat.poisson_ratio) + ")");
  if (!(std::isfinite(mat.yield_strength) && mat.yield_strength > 0))
    throw FemError("material.yield_strength", "must be a finite number > 0 Pa (got " + str(mat.yield_strength) + ")");
}

// What uses each node, gathered while the parts of the model are checked.
struct NodeUse {
  std::vector<char> in_element, supported, in_link;  // #N
  std::vector<int> slave_of;                         // #N, the rigid link a node is a slave of, -1 if none
  explicit NodeUse(int n) : in_element(n, 0), supported(n, 0), in_link(n, 0), slave_of(n, -1) {}
};

void check_elements(const ShellModel& m, NodeUse& use) {
  if (m.triangles.empty()) throw FemError("triangles", "the model has no elements");
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (!m.nodes[i].allFinite()) throw FemError("node " + std::to_string(i), "coordinate is not finite");
  for (size_t e = 0; e < m.triangles.size(); ++e) {
    const auto& t = m.triangles[e];
    for (int k = 0; k < 3; ++k) {
      check_node(m, t[k], "triangle " + std::to_string(e));
      use.in_element[t[k]] = 1;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw FemError("triangle " + std::to_string(e), "repeats a node");
  }
}

void check_supports(const ShellModel& m, NodeUse& use) {
  for (const NodeSupport& s : m.supports) {
    check_node(m, s.node, "support");
    if (std::any_of(s.fixed.begin(), s.fixed.end(), [](bool b) { return b; })) use.supported[s.node] = 1;
  }
}

void check_rigid_links(const ShellModel& m, NodeUse& use) {
  for (size_t l = 0; l < m.rigid_links.size(); ++l) {
    const RigidLink& link = m.rigid_links[l];
    const std::string name = "rigid_links[" + std::to_string(l) + "]";
    check_node(m, link.master, name + ".master");
    if (link.slaves.empty()) throw FemError(name, "has no slave nodes");
    use.in_link[link.master] = 1;
    for (int s : link.slaves) {
      check_node(m, s, name + ".slaves");
      if (s == link.master) throw FemError(name, "node " + std::to_string(s) + " is its own master");
      if (use.slave_of[s] >= 0)
        throw FemError(name, "node " + std::to_string(s) + " is already a slave of rigid_links[" +
                                 std::to_string(use.slave_of[s]) + "]");
      if (use.supported[s])
        throw FemError(name, "slave node " + std::to_string(s) +
                                 " also has a support; support its master instead");
      use.slave_of[s] = static_cast<int>(l);
      use.in_link[s] = 1;
    }
  }
  for (const RigidLink& link : m.rigid_links)
    if (use.slave_of[link.master] >= 0)
      throw FemError("rigid link master " + std::to_string(link.master),
                     "is itself a slave of another link (chained links are not supported; merge them)");
}

void check_nodal_loads(const ShellModel& m, const NodeUse& use, const std::vector<NodalLoad>& loads,
                       const std::string& where) {
  for (size_t i = 0; i < loads.size(); ++i) {
    const NodalLoad& f = loads[i];
    const std::string field = where + "[" + std::to_string(i) + "]";
    check_node(m, f.node, field);
    if (!f.force.allFinite() || !f.moment.allFinite()) throw FemError(field, "force or moment is not finite");
    if (!use.in_element[f.node] && !use.in_link[f.node])
      throw FemError(field, "acts on node " + std::to_string(f.node) + ", which no element or rigid link uses");
  }
}

// Every named case must load the model: a case without load has no stress
// state to buckle from and a zero deflection that would pass any check.
void check_loads(const ShellModel& m, const NodeUse& use) {
  check_nodal_loads(m, use, m.loads, "loads");
  for (size_t c = 0; c < m.load_cases.size(); ++c) {
    const ShellLoadCase& lc = m.load_cases[c];
    const std::string field = "load_cases[" + std::to_string(c) + "] '" + lc.name + "'";
    check_nodal_loads(m, use, lc.loads, field + ".loads");
    const bool loaded = std::any_of(lc.loads.begin(), lc.loads.end(), [](const NodalLoad& f) {
      return f.force.squaredNorm() > 0 || f.moment.squaredNorm() > 0;
    });
    if (!loaded) throw FemError(field, "has no non-zero force or moment");
  }
  if (m.load_node >= 0) check_node(m, m.load_node, "load_node");
}

// A point mass must be a positive, finite mass with a symmetric positive
// semi-definite inertia on a node the model uses.
void check_point_masses(const ShellModel& m, const NodeUse& use) {
  for (size_t i = 0; i < m.point_masses.size(); ++i) {
    const PointMass& p = m.point_masses[i];
    const std::string field = "point_masses[" + std::to_string(i) + "]";
    check_node(m, p.node, field);
    if (!use.in_element[p.node] && !use.in_link[p.node])
      throw FemError(field, "sits on node " + std::to_string(p.node) + ", which no element or rigid link uses");
    if (!std::isfinite(p.mass) || !(p.mass > 0))
      throw FemError(field + ".mass", "must be a finite number > 0 kg (got " + str(p.mass) + ")");
    if (!p.offset.allFinite() || !p.inertia.allFinite())
      throw FemError(field, "offset or inertia is not finite");
    const double scale = std::max(p.inertia.cwiseAbs().maxCoeff(), 1e-300);
    if ((p.inertia - p.inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
      throw FemError(field + ".inertia", "is not symmetric");
    if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(p.inertia).eigenvalues().minCoeff() < -1e-12 * scale)
      throw FemError(field + ".inertia", "has a negative principal moment");
  }
}

// Every connected patch (elements joined through shared nodes and rigid
// links) must reach a support; otherwise K is singular.
void check_every_patch_supported(const ShellModel& m, const NodeUse& use) {
  if (!std::any_of(use.supported.begin(), use.supported.end(), [](char c) { return c != 0; }))
    throw FemError("supports", "the model has no supported node, so it is a free mechanism");
  const int n = static_cast<int>(m.nodes.size());
  UnionFind uf(n);
  for (const auto& t : m.triangles) {
    uf.join(t[0], t[1]);
    uf.join(t[1], t[2]);
  }
  for (const RigidLink& link : m.rigid_links)
    for (int s : link.slaves) uf.join(s, link.master);
  std::vector<char> root_supported(n, 0);
  for (int i = 0; i < n; ++i)
    if (use.supported[i]) root_supported[uf.find(i)] = 1;
  for (size_t e = 0; e < m.triangles.size(); ++e) {
    if (!root_supported[uf.find(m.triangles[e][0])]) {
      const Vec3 c = (m.nodes[m.triangles[e][0]] + m.nodes[m.triangles[e][1]] + m.nodes[m.triangles[e][2]]) / 3.0;
      std::ostringstream s;
      s << "belongs to a patch connected to no support (a disconnected part; element centroid at " << c.x() << ", "
        << c.y() << ", " << c.z() << " m)";
      throw FemError("triangle " + std::to_string(e), s.str());
    }
  }
}

}  // namespace

void validate_shell_model(const ShellModel& m) {
  check_material(m.material);
  NodeUse use(static_cast<int>(m.nodes.size()));
  check_elements(m, use);
  check_supports(m, use);
  check_rigid_links(m, use);
  check_loads(m, use);
  check_point_masses(m, use);
  check_every_patch_supported(m, use);
}

// ---------------------------------------------------------------- solver

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Boundary nodes whose incident triangles' angles at the node add up to more
// than `min_angle` (rad): re-entrant corners of the shell's outline. Where a
// fold stops inside its parent's edge the parent gives pi and the child about
// pi/2, so the corner is ~3 pi/2 wide; a flat extension narrower than its
// parent's edge makes the same notch in one plane. The plate and sharp-fold
// models are singular there (the stress grows without bound as h -> 0), just
// as at a clamp. A fold over a whole edge ends at pi/2 + pi/2 = pi and stays
// in the rule. A boundary node is one on an edge that only one triangle uses.
std::vector<int> find_reentrant_corners(const ShellModel& m, double min_angle) {
  const int n_nodes = static_cast<int>(m.nodes.size());
  // Runs once per solve (composition solves hundreds of candidates): sorted
  // edge keys rather than a hash map.
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * m.triangles.size());
  std::vector<double> angle_sum(n_nodes, 0.0);
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      edges.push_back((static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b)));
      const Vec3 u = m.nodes[b] - m.nodes[a];
      const Vec3 v = m.nodes[t[(k + 2) % 3]] - m.nodes[a];
      angle_sum[a] += std::atan2(u.cross(v).norm(), u.dot(v));
    }
  std::sort(edges.begin(), edges.end());
  std::vector<char> on_boundary(n_nodes, 0);
  for (size_t i = 0, j = 0; i < edges.size(); i = j) {
    for (j = i + 1; j < edges.size() && edges[j] == edges[i]; ++j) {
    }
    if (j - i == 1) {  // an edge only one triangle uses
      on_boundary[edges[i] >> 32] = 1;
      on_boundary[edges[i] & 0xffffffffu] = 1;
    }
  }
  std::vector<int> corners;
  for (int i = 0; i < n_nodes; ++i)
    if (on_boundary[i] && angle_sum[i] > min_angle) corners.push_back(i);
  return corners;
}

// The model's load node, else the loaded node that moves most (-1 without loads).
int deflection_node(const ShellModel& m, const std::vector<NodalLoad>& loads, const std::vector<Vector6d>& u) {
  if (m.load_node >= 0) return m.load_node;
  int node = -1;
  double best = -1;
  for (const NodalLoad& load : loads) {
    const double d = u[load.node].head<3>().norm();
    if (d > best) {
      best = d;
      node = load.node;
    }
  }
  return node;
}

// Every case's element stresses, each element's operator built once for all of them.
void element_stresses(const ShellModel& m, const ShellElementOptions& element, std::vector<ShellResult>& cases) {
  const int n_elem = static_cast<int>(m.triangles.size());
  for (ShellResult& res : cases) {
    res.von_mises_top.resize(n_elem);
    res.von_mises_bottom.resize(n_elem);
  }
  for (int e = 0; e < n_elem; ++e) {
    const auto& t = m.triangles[e];
    const ShellStressOperator op = shell_stress_operator({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, m.material, element);
    for (ShellResult& res : cases) {
      Vector18d ue;
      for (int k = 0; k < 3; ++k) ue.segment<6>(6 * k) = res.displacements[t[k]];
      const ShellStress st = shell_element_stress(op, ue);
      res.von_mises_top[e] = st.von_mises_top;
      res.von_mises_bottom[e] = st.von_mises_bottom;
    }
  }
}

struct MeshSizes {
  std::vector<Vec3> centroid;     // #E, m
  std::vector<double> node_size;  // #N, longest incident edge, m
};

MeshSizes mesh_sizes(const ShellModel& m) {
  MeshSizes ms;
  ms.centroid.resize(m.triangles.size());
  ms.node_size.assign(m.nodes.size(), 0.0);
  for (size_t e = 0; e < m.triangles.size(); ++e) {
    const auto& t = m.triangles[e];
    ms.centroid[e] = (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const double len = (m.nodes[t[(k + 1) % 3]] - m.nodes[t[k]]).norm();
      ms.node_size[t[k]] = std::max(ms.node_size[t[k]], len);
      ms.node_size[t[(k + 1) % 3]] = std::max(ms.node_size[t[(k + 1) % 3]], len);
    }
  }
  return ms;
}

struct SingularPoints {
  std::vector<int> nodes;      // singular nodes that carry elements
  std::vector<double> radius;  // #N, m, exclusion radius of each singular point
  double rmax = 0;             // m, largest radius
};

// Singular points: supported nodes, rigid-link nodes that carry elements, and
// re-entrant corners of the boundary.
SingularPoints singular_points(const ShellModel& m, const std::vector<int>& reentrant_corners,
                               const std::vector<double>& node_size, const ShellSolveOptions& options) {
  const int n_nodes = static_cast<int>(m.nodes.size());
  std::vector<char> singular(n_nodes, 0);
  for (const NodeSupport& sp : m.supports) singular[sp.node] = 1;
  for (const RigidLink& link : m.rigid_links) {
    singular[link.master] = 1;
    for (int sl : link.slaves) singular[sl] = 1;
  }
  for (int i : reentrant_corners) singular[i] = 1;
  SingularPoints sp;
  const double base_radius = options.stress_exclusion_thicknesses * m.material.thickness;
  sp.radius.assign(n_nodes, 0.0);
  for (int i : reentrant_corners) sp.radius[i] = base_radius + std::max(node_size[i], options.reentrant_corner_clearance);
  for (int i = 0; i < n_nodes; ++i)
    if (singular[i] && node_size[i] > 0) {
      sp.nodes.push_back(i);
      sp.radius[i] = std::max(sp.radius[i], base_radius + node_size[i]);
      sp.rmax = std::max(sp.rmax, sp.radius[i]);
    }
  return sp;
}

// Uniform hash grid of cell `cell` (m): a centroid only needs its 27 neighbour cells.
struct CellKey {
  double cell;
  std::int64_t operator()(const Vec3& p, int dx, int dy, int dz) const {
    const auto c = [this](double v, int d) { return static_cast<std::int64_t>(std::floor(v / cell)) + d; };
    return (c(p.x(), dx) * 73856093) ^ (c(p.y(), dy) * 19349663) ^ (c(p.z(), dz) * 83492791);
  }
};

// #E: true where the element's centroid lies within a singular point's radius.
std::vector<bool> elements_near_singular_points(const ShellModel& m, const std::vector<Vec3>& centroid,
                                                const SingularPoints& sp) {
  const int n_elem = static_cast<int>(m.triangles.size());
  std::vector<bool> excluded(n_elem, false);
  if (sp.nodes.empty() || !(sp.rmax > 0)) return excluded;
  const CellKey key{sp.rmax};
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  for (int i : sp.nodes) grid[key(m.nodes[i], 0, 0, 0)].push_back(i);
  for (int e = 0; e < n_elem; ++e) {
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx)
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          auto it = grid.find(key(centroid[e], dx, dy, dz));
          if (it == grid.end()) continue;
          for (int i : it->second) {
            if ((centroid[e] - m.nodes[i]).squaredNorm() < sp.radius[i] * sp.radius[i]) {
              near = true;
              break;
            }
          }
        }
    excluded[e] = near;
  }
  return excluded;
}

void take_max_von_mises(ShellResult& res, bool honour_rule) {
  res.max_von_mises = 0;
  res.max_von_mises_element = -1;
  for (int e = 0; e < static_cast<int>(res.von_mises_top.size()); ++e) {
    if (honour_rule && res.stress_excluded[e]) continue;
    const double v = std::max(res.von_mises_top[e], res.von_mises_bottom[e]);
    if (v > res.max_von_mises || res.max_von_mises_element < 0) {
      res.max_von_mises = v;
      res.max_von_mises_element = e;
    }
  }
}

// What the stress rule takes from the model alone: the same for every case,
// so a solve of several cases finds it once.
struct StressRuleGeometry {
  std::vector<int> reentrant_corners;
  std::vector<bool> excluded;  // #E, within a singular point's radius
};

StressRuleGeometry stress_rule_geometry(const ShellModel& m, const ShellSolveOptions& options) {
  StressRuleGeometry g;
  const MeshSizes sizes = mesh_sizes(m);
  g.reentrant_corners = find_reentrant_corners(m, options.reentrant_corner_angle);
  const SingularPoints sp = singular_points(m, g.reentrant_corners, sizes.node_size, options);
  g.excluded = elements_near_singular_points(m, sizes.centroid, sp);
  return g;
}

// The elements the stress rule leaves out, the maximum over the rest of the
// stresses element_stresses set, and the margin of safety.
void apply_stress_rule(const ShellModel& m, const ShellSolveOptions& options, const StressRuleGeometry& g,
                       ShellResult& res) {
  res.reentrant_corners = g.reentrant_corners;
  res.stress_excluded = g.excluded;
  take_max_von_mises(res, true);
  if (res.max_von_mises_element < 0) {
    res.stress_rule_fell_back = true;
    take_max_von_mises(res, false);
  }
  res.margin_of_safety = res.max_von_mises > 0
                             ? m.material.yield_strength / (options.safety_factor * res.max_von_mises) - 1.0
                             : std::numeric_limits<double>::infinity();
}

// The static answer of one case from its reduced load and displacement vectors,
// before its stresses.
ShellResult finish_case(const ShellModel& m, const DofMap& map, const ShellLoadCase& lc, const Eigen::VectorXd& f,
                        const Eigen::VectorXd& uh) {
  ShellResult res;
  res.case_name = lc.name;
  res.reduced_dofs = map.reduced;
  if (!uh.allFinite()) throw FemError("solution", "the solve produced non-finite displacements");
  res.displacements = expand_displacements(map, uh, static_cast<int>(m.nodes.size()));
  res.compliance = f.dot(uh);
  res.load_node = deflection_node(m, lc.loads, res.displacements);
  if (res.load_node >= 0) {
    const Vec3 u = res.displacements[res.load_node].head<3>();
    res.load_deflection = u.norm();
    Vec3 force = Vec3::Zero();
    for (const NodalLoad& load : lc.loads) force += load.force;
    if (force.norm() > 0) res.deflection_along_load = u.dot(force.normalized());
  }
  return res;
}

}  // namespace

ShellSolver::ShellSolver() : impl_(std::make_unique<Impl>()) {}
ShellSolver::~ShellSolver() = default;
ShellSolver::ShellSolver(ShellSolver&&) noexcept = default;
ShellSolver& ShellSolver::operator=(ShellSolver&&) noexcept = default;
int ShellSolver::symbolic_analyses() const { return impl_->factor.symbolic_analyses(); }

bool StiffnessInputs::same(const ShellModel& m, const ShellSolveOptions& o) const {
  const Material& a = material;
  const Material& b = m.material;
  const ShellElementOptions& e = element;
  const ShellElementOptions& f = o.element;
  return backend == o.backend && singular_pivot_ratio == o.singular_pivot_ratio && a.youngs_modulus == b.youngs_modulus &&
         a.poisson_ratio == b.poisson_ratio && a.thickness == b.thickness && e.alpha_b == f.alpha_b &&
         e.beta0 == f.beta0 && e.transverse_shear == f.transverse_shear && e.shear_correction == f.shear_correction &&
         nodes == m.nodes && triangles == m.triangles &&
         std::equal(supports.begin(), supports.end(), m.supports.begin(), m.supports.end(),
                    [](const NodeSupport& x, const NodeSupport& y) { return x.node == y.node && x.fixed == y.fixed; }) &&
         std::equal(rigid_links.begin(), rigid_links.end(), m.rigid_links.begin(), m.rigid_links.end(),
                    [](const RigidLink& x, const RigidLink& y) { return x.master == y.master && x.slaves == y.slaves; });
}

void StiffnessInputs::keep(const ShellModel& m, const ShellSolveOptions& o) {
  nodes = m.nodes;
  triangles = m.triangles;
  supports = m.supports;
  rigid_links = m.rigid_links;
  material = m.material;
  element = o.element;
  backend = o.backend;
  singular_pivot_ratio = o.singular_pivot_ratio;
}

void ShellSolver::Impl::prepare(const ShellModel& m, const ShellSolveOptions& options, ShellResult& timing) {
  if (prepared && inputs.same(m, options)) {
    timing.pattern_reused = true;
    return;
  }
  prepared = false;  // until the new factor stands (factorise may throw)
  auto t0 = Clock::now();
  map = build_dof_map(m);
  if (map.reduced == 0) throw FemError("supports", "every DOF is fixed; there is nothing to solve");
  stiffness = assemble_stiffness(m, map, options.element);
  timing.assemble_seconds = seconds_since(t0);
  t0 = Clock::now();
  timing.pattern_reused = factor.factorise(stiffness, options.backend, options.singular_pivot_ratio).pattern_reused;
  timing.factor_seconds = seconds_since(t0);
  inputs.keep(m, options);
  prepared = true;
}

std::vector<ShellResult> ShellSolver::Impl::solve(const ShellModel& m, const std::vector<ShellLoadCase>& cases,
                                                  const ShellSolveOptions& options) {
  ShellResult timing;
  prepare(m, options, timing);
  auto t0 = Clock::now();
  const int n_nodes = static_cast<int>(m.nodes.size());
  Eigen::MatrixXd F(map.reduced, static_cast<Eigen::Index>(cases.size()));
  for (size_t c = 0; c < cases.size(); ++c) F.col(c) = assemble_load(cases[c].loads, map, n_nodes);
  timing.assemble_seconds += seconds_since(t0);
  t0 = Clock::now();
  const Eigen::MatrixXd U = factor.solve(F);  // one factorisation, every case
  const double solve_seconds = seconds_since(t0);
  std::vector<ShellResult> results;
  for (size_t c = 0; c < cases.size(); ++c) results.push_back(finish_case(m, map, cases[c], F.col(c), U.col(c)));
  t0 = Clock::now();
  element_stresses(m, options.element, results);
  const StressRuleGeometry stress_rule = stress_rule_geometry(m, options);
  for (ShellResult& res : results) apply_stress_rule(m, options, stress_rule, res);
  const double stress_seconds = seconds_since(t0);
  for (ShellResult& res : results) {  // each case's times are the shared steps'
    res.pattern_reused = timing.pattern_reused;
    res.assemble_seconds = timing.assemble_seconds;
    res.factor_seconds = timing.factor_seconds;
    res.solve_seconds = solve_seconds;
    res.stress_seconds = stress_seconds;
  }
  return results;
}

ShellResult ShellSolver::solve(const ShellModel& m, const ShellSolveOptions& options) {
  validate_shell_model(m);
  return impl_->solve(m, {ShellLoadCase{"design", m.loads}}, options).front();
}

std::vector<ShellResult> ShellSolver::solve_cases(const ShellModel& m, const ShellSolveOptions& options) {
  validate_shell_model(m);
  return impl_->solve(m, m.cases(), options);
}

ShellResult solve_shell(const ShellModel& model, const ShellSolveOptions& options) {
  ShellSolver solver;
  return solver.solve(model, options);
}

std::vector<ShellResult> solve_shell_cases(const ShellModel& model, const ShellSolveOptions& options) {
  ShellSolver solver;
  return solver.solve_cases(model, options);
}

}  // namespace sheetgen
