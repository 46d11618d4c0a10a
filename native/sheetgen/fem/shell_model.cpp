#include "sheetgen/fem/shell_model.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

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

void check_loads(const ShellModel& m, const NodeUse& use) {
  for (size_t i = 0; i < m.loads.size(); ++i) {
    const NodalLoad& f = m.loads[i];
    check_node(m, f.node, "loads[" + std::to_string(i) + "]");
    if (!f.force.allFinite() || !f.moment.allFinite())
      throw FemError("loads[" + std::to_string(i) + "]", "force or moment is not finite");
    if (!use.in_element[f.node] && !use.in_link[f.node])
      throw FemError("loads[" + std::to_string(i) + "]",
                     "acts on node " + std::to_string(f.node) + ", which no element or rigid link uses");
  }
  if (m.load_node >= 0) check_node(m, m.load_node, "load_node");
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
  check_every_patch_supported(m, use);
}

// ---------------------------------------------------------------- solver

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Full DOF (6 per node) -> linear combination of reduced DOFs: u = T u_hat.
struct DofMap {
  std::vector<int> start;  // 6 #N + 1, CSR offsets into index/coef
  std::vector<int> index;  // reduced DOF
  std::vector<double> coef;
  int reduced = 0;
};

DofMap build_dof_map(const ShellModel& m) {
  const int n = static_cast<int>(m.nodes.size());
  std::vector<std::array<bool, 6>> fixed(n, std::array<bool, 6>{});
  for (const NodeSupport& s : m.supports)
    for (int d = 0; d < 6; ++d) fixed[s.node][d] = fixed[s.node][d] || s.fixed[d];
  std::vector<char> active(n, 0);
  for (const auto& t : m.triangles)
    for (int k : t) active[k] = 1;
  std::vector<int> slave_link(n, -1);
  for (size_t l = 0; l < m.rigid_links.size(); ++l) {
    active[m.rigid_links[l].master] = 1;
    for (int s : m.rigid_links[l].slaves) slave_link[s] = static_cast<int>(l);
  }
  DofMap map;
  std::vector<int> red(6 * static_cast<size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (!active[i] || slave_link[i] >= 0) continue;
    for (int d = 0; d < 6; ++d)
      if (!fixed[i][d]) red[6 * i + d] = map.reduced++;
  }
  map.start.assign(6 * static_cast<size_t>(n) + 1, 0);
  map.index.reserve(6 * static_cast<size_t>(n));
  map.coef.reserve(6 * static_cast<size_t>(n));
  auto push = [&](int r, double c) {
    if (r >= 0 && c != 0.0) {
      map.index.push_back(r);
      map.coef.push_back(c);
    }
  };
  for (int i = 0; i < n; ++i) {
    const int l = slave_link[i];
    for (int d = 0; d < 6; ++d) {
      if (l < 0) {
        push(red[6 * i + d], 1.0);
      } else {
        const int mi = m.rigid_links[l].master;
        const Vec3 r = m.nodes[i] - m.nodes[mi];
        const int* rm = &red[6 * mi];
        push(rm[d], 1.0);  // u_s = u_m + theta_m x r; theta_s = theta_m
        if (d == 0) { push(rm[4], r.z()); push(rm[5], -r.y()); }
        if (d == 1) { push(rm[5], r.x()); push(rm[3], -r.z()); }
        if (d == 2) { push(rm[3], r.y()); push(rm[4], -r.x()); }
      }
      map.start[6 * i + d + 1] = static_cast<int>(map.index.size());
    }
  }
  return map;
}

std::uint64_t pattern_hash(const SparseMatrix& K) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the index arrays
  auto mix = [&h](std::uint64_t v) {
    h ^= v;
    h *= 1099511628211ull;
  };
  mix(static_cast<std::uint64_t>(K.rows()));
  for (Eigen::Index j = 0; j <= K.cols(); ++j) mix(static_cast<std::uint64_t>(K.outerIndexPtr()[j]));
  for (Eigen::Index k = 0; k < K.nonZeros(); ++k) mix(static_cast<std::uint64_t>(K.innerIndexPtr()[k]));
  return h;
}

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

// Gives access to the CHOLMOD factor so the pivots can be checked for a
// mechanism (CHOLMOD only fails on non-positive pivots, not on tiny ones).
class CholmodLlt : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  // Smallest L_jj^2 / K_jj over all columns (1 for a perfectly diagonal K).
  double min_pivot_ratio(const Eigen::VectorXd& diag) const {
    const cholmod_factor* L = this->m_cholmodFactor;
    if (!L || !L->is_super) return 1.0;
    const int* sup = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    const int* px = static_cast<const int*>(L->px);
    const int* perm = static_cast<const int*>(L->Perm);
    const double* x = static_cast<const double*>(L->x);
    double worst = std::numeric_limits<double>::infinity();
    for (size_t s = 0; s < L->nsuper; ++s) {
      const int k1 = sup[s], k2 = sup[s + 1];
      const int nsrow = pi[s + 1] - pi[s];
      for (int j = k1; j < k2; ++j) {
        const double ljj = x[px[s] + (j - k1) + static_cast<size_t>(j - k1) * nsrow];
        const double kjj = diag(perm ? perm[j] : j);
        worst = std::min(worst, kjj > 0 ? ljj * ljj / kjj : 0.0);
      }
    }
    return worst;
  }
};

using EigenLdlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;

// Smallest D_jj / K_jj over all columns, in the factor's (permuted) order.
double min_pivot_ratio(const EigenLdlt& ldlt, const Eigen::VectorXd& diag) {
  const int N = static_cast<int>(diag.size());
  const Eigen::VectorXd& D = ldlt.vectorD();
  const auto& P = ldlt.permutationP().indices();
  Eigen::VectorXd pdiag(N);
  for (int i = 0; i < N; ++i) pdiag(P(i)) = diag(i);
  double pivot_ratio = std::numeric_limits<double>::infinity();
  for (int j = 0; j < N; ++j) pivot_ratio = std::min(pivot_ratio, pdiag(j) > 0 ? D(j) / pdiag(j) : 0.0);
  return pivot_ratio;
}

// Adds T_e^T Ke T_e of one element to the lower triangle of K_hat.
void add_element_triplets(std::vector<Eigen::Triplet<double, int>>& triplets, const DofMap& map, const std::array<int, 3>& t,
                          const Matrix18d& Ke) {
  int beg[18], end[18];
  for (int a = 0; a < 18; ++a) {
    const int full = 6 * t[a / 6] + a % 6;
    beg[a] = map.start[full];
    end[a] = map.start[full + 1];
  }
  for (int a = 0; a < 18; ++a)
    for (int pa = beg[a]; pa < end[a]; ++pa) {
      const int ia = map.index[pa];
      const double ca = map.coef[pa];
      for (int b = 0; b < 18; ++b)
        for (int pb = beg[b]; pb < end[b]; ++pb) {
          const int ib = map.index[pb];
          if (ib > ia) continue;  // lower triangle only
          triplets.emplace_back(ia, ib, ca * map.coef[pb] * Ke(a, b));
        }
    }
}

// K_hat = T^T K T, lower triangle.
SparseMatrix assemble_stiffness(const ShellModel& m, const DofMap& map, const ShellElementOptions& element) {
  const int n_elem = static_cast<int>(m.triangles.size());
  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(static_cast<size_t>(n_elem) * 171);  // 18*19/2 per element
  for (int e = 0; e < n_elem; ++e) {
    const auto& t = m.triangles[e];
    const Matrix18d Ke = shell_element_stiffness({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, m.material, element);
    add_element_triplets(triplets, map, t, Ke);
  }
  SparseMatrix K(map.reduced, map.reduced);
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

// f_hat = T^T f.
Eigen::VectorXd assemble_load(const ShellModel& m, const DofMap& map) {
  const int n_nodes = static_cast<int>(m.nodes.size());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map.reduced);
  std::vector<Vector6d> f_full(n_nodes, Vector6d::Zero());
  for (const NodalLoad& load : m.loads) {
    f_full[load.node].head<3>() += load.force;
    f_full[load.node].tail<3>() += load.moment;
  }
  for (int i = 0; i < n_nodes; ++i)
    for (int d = 0; d < 6; ++d)
      for (int p = map.start[6 * i + d]; p < map.start[6 * i + d + 1]; ++p)
        f(map.index[p]) += map.coef[p] * f_full[i](d);
  return f;
}

// u = T u_hat.
std::vector<Vector6d> expand_displacements(const DofMap& map, const Eigen::VectorXd& uh, int n_nodes) {
  std::vector<Vector6d> u(n_nodes, Vector6d::Zero());
  for (int i = 0; i < n_nodes; ++i)
    for (int d = 0; d < 6; ++d) {
      double v = 0;
      for (int p = map.start[6 * i + d]; p < map.start[6 * i + d + 1]; ++p) v += map.coef[p] * uh(map.index[p]);
      u[i](d) = v;
    }
  return u;
}

// The model's load node, else the loaded node that moves most (-1 without loads).
int deflection_node(const ShellModel& m, const std::vector<Vector6d>& u) {
  if (m.load_node >= 0) return m.load_node;
  int node = -1;
  double best = -1;
  for (const NodalLoad& load : m.loads) {
    const double d = u[load.node].head<3>().norm();
    if (d > best) {
      best = d;
      node = load.node;
    }
  }
  return node;
}

void element_stresses(const ShellModel& m, const ShellElementOptions& element, ShellResult& res) {
  const int n_elem = static_cast<int>(m.triangles.size());
  res.von_mises_top.resize(n_elem);
  res.von_mises_bottom.resize(n_elem);
  for (int e = 0; e < n_elem; ++e) {
    const auto& t = m.triangles[e];
    Vector18d ue;
    for (int k = 0; k < 3; ++k) ue.segment<6>(6 * k) = res.displacements[t[k]];
    const ShellStress st = shell_element_stress({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, m.material, ue, element);
    res.von_mises_top[e] = st.von_mises_top;
    res.von_mises_bottom[e] = st.von_mises_bottom;
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

// Element stresses, the elements the stress rule leaves out, the maximum over
// the rest and the margin of safety.
void apply_stress_rule(const ShellModel& m, const ShellSolveOptions& options, ShellResult& res) {
  element_stresses(m, options.element, res);
  const MeshSizes sizes = mesh_sizes(m);
  res.reentrant_corners = find_reentrant_corners(m, options.reentrant_corner_angle);
  const SingularPoints sp = singular_points(m, res.reentrant_corners, sizes.node_size, options);
  res.stress_excluded = elements_near_singular_points(m, sizes.centroid, sp);
  take_max_von_mises(res, true);
  if (res.max_von_mises_element < 0) {
    res.stress_rule_fell_back = true;
    take_max_von_mises(res, false);
  }
  res.margin_of_safety = res.max_von_mises > 0
                             ? m.material.yield_strength / (options.safety_factor * res.max_von_mises) - 1.0
                             : std::numeric_limits<double>::infinity();
}

}  // namespace

struct ShellSolver::Impl {
  std::uint64_t hash = 0;
  ShellSolverBackend backend = ShellSolverBackend::kEigenSimplicialLdlt;
  bool analysed = false;
  int analyses = 0;
  CholmodLlt cholmod;
  EigenLdlt ldlt;

  // Factorises K, reusing the symbolic analysis while the pattern repeats
  // (returns whether it did); throws on a singular K.
  bool factorise(const SparseMatrix& K, ShellSolverBackend use, double singular_pivot_ratio) {
    const std::uint64_t h = pattern_hash(K);
    const bool reuse = analysed && hash == h && backend == use;
    const Eigen::VectorXd diag = K.diagonal();
    double pivot_ratio = 1.0;
    bool ok = true;
    if (use == ShellSolverBackend::kCholmodSupernodal) {
      if (!reuse) cholmod.analyzePattern(K);
      cholmod.factorize(K);
      ok = cholmod.info() == Eigen::Success;
      if (ok) pivot_ratio = cholmod.min_pivot_ratio(diag);
    } else {
      if (!reuse) ldlt.analyzePattern(K);
      ldlt.factorize(K);
      ok = ldlt.info() == Eigen::Success;
      if (ok) pivot_ratio = min_pivot_ratio(ldlt, diag);
    }
    analysed = true;
    hash = h;
    backend = use;
    if (!reuse) ++analyses;
    if (!ok || !(pivot_ratio > singular_pivot_ratio)) {
      analysed = false;  // a failed factor leaves the solver in an unknown state
      throw FemError("stiffness", "the stiffness matrix is singular (smallest pivot ratio " + str(pivot_ratio) +
                                      "): the supports leave a rigid-body mode or a mechanism free");
    }
    return reuse;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& f, ShellSolverBackend use) {
    return use == ShellSolverBackend::kCholmodSupernodal ? Eigen::VectorXd(cholmod.solve(f)) : Eigen::VectorXd(ldlt.solve(f));
  }
};

ShellSolver::ShellSolver() : impl_(std::make_unique<Impl>()) {}
ShellSolver::~ShellSolver() = default;
ShellSolver::ShellSolver(ShellSolver&&) noexcept = default;
ShellSolver& ShellSolver::operator=(ShellSolver&&) noexcept = default;
int ShellSolver::symbolic_analyses() const { return impl_->analyses; }

ShellResult ShellSolver::solve(const ShellModel& m, const ShellSolveOptions& options) {
  validate_shell_model(m);
  ShellResult res;

  auto t0 = Clock::now();
  const DofMap map = build_dof_map(m);
  res.reduced_dofs = map.reduced;
  if (map.reduced == 0) throw FemError("supports", "every DOF is fixed; there is nothing to solve");
  const SparseMatrix K = assemble_stiffness(m, map, options.element);
  const Eigen::VectorXd f = assemble_load(m, map);
  res.assemble_seconds = seconds_since(t0);

  t0 = Clock::now();
  res.pattern_reused = impl_->factorise(K, options.backend, options.singular_pivot_ratio);
  res.factor_seconds = seconds_since(t0);

  t0 = Clock::now();
  const Eigen::VectorXd uh = impl_->solve(f, options.backend);
  if (!uh.allFinite()) throw FemError("solution", "the solve produced non-finite displacements");
  res.displacements = expand_displacements(map, uh, static_cast<int>(m.nodes.size()));
  res.compliance = f.dot(uh);
  res.load_node = deflection_node(m, res.displacements);
  if (res.load_node >= 0) res.load_deflection = res.displacements[res.load_node].head<3>().norm();
  res.solve_seconds = seconds_since(t0);

  t0 = Clock::now();
  apply_stress_rule(m, options, res);
  res.stress_seconds = seconds_since(t0);
  return res;
}

ShellResult solve_shell(const ShellModel& model, const ShellSolveOptions& options) {
  ShellSolver solver;
  return solver.solve(model, options);
}

}  // namespace sheetgen
