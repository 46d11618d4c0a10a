#include "sheetgen/fem/shell_assembly.hpp"

#include "sheetgen/fem/node_block_pattern.hpp"

namespace sheetgen {

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
      if (!fixed[i][d]) {
        red[6 * i + d] = map.reduced++;
        map.owner.push_back(i);
      }
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

namespace {

using Triplets = std::vector<Eigen::Triplet<double, int>>;

// Calls sink(ia, ib, value) for each term of T_a^T A T_b, the DOF lists
// (full DOF ids) `dofs` of one element or node, lower triangle only, in a
// fixed order (the order the terms of an entry are summed in).
template <int N, class Sink>
void for_each_lower_term(const DofMap& map, const std::array<int, N>& dofs, const Eigen::Matrix<double, N, N>& A,
                         Sink&& sink) {
  int beg[N], end[N];
  for (int a = 0; a < N; ++a) {
    beg[a] = map.start[dofs[a]];
    end[a] = map.start[dofs[a] + 1];
  }
  for (int a = 0; a < N; ++a)
    for (int pa = beg[a]; pa < end[a]; ++pa) {
      const int ia = map.index[pa];
      const double ca = map.coef[pa];
      for (int b = 0; b < N; ++b)
        for (int pb = beg[b]; pb < end[b]; ++pb) {
          const int ib = map.index[pb];
          if (ib > ia) continue;  // lower triangle only
          sink(ia, ib, ca * map.coef[pb] * A(a, b));
        }
    }
}

template <int N>
void add_triplets(Triplets& triplets, const DofMap& map, const std::array<int, N>& dofs,
                  const Eigen::Matrix<double, N, N>& A) {
  for_each_lower_term<N>(map, dofs, A, [&](int ia, int ib, double v) { triplets.emplace_back(ia, ib, v); });
}

// The same terms added into the pattern's values, in the same order.
template <int N>
void add_in_place(double* values, NodeBlockPattern& pattern, const DofMap& map, const std::array<int, N>& dofs,
                  const Eigen::Matrix<double, N, N>& A) {
  pattern.begin_block(map, dofs.data(), N);
  for_each_lower_term<N>(map, dofs, A, [&](int ia, int ib, double v) { values[pattern.position(ia, ib)] += v; });
}

}  // namespace

SparseMatrix assemble_elements_by_triplets(const ShellModel& m, const DofMap& map,
                                           const std::function<Matrix18d(int element)>& element_matrix,
                                           const std::vector<NodalBlock>& nodal_blocks) {
  const int n_elem = static_cast<int>(m.triangles.size());
  // One list per thread, emptied and refilled by every assembly: it is the
  // largest buffer of a triplet assembly (16 B x 171 per element, 30 MB for
  // 11 000 elements), and a fresh one each call was most of a solve's page
  // faults (docs/benchmarks.md "Allocator").
  thread_local Triplets triplets;
  triplets.clear();
  triplets.reserve(static_cast<size_t>(n_elem) * 171 + nodal_blocks.size() * 21);  // 18*19/2 per element
  for (int e = 0; e < n_elem; ++e) {
    add_triplets<18>(triplets, map, element_dofs(m.triangles[e]), element_matrix(e));
  }
  for (const NodalBlock& b : nodal_blocks) add_triplets<6>(triplets, map, node_dofs(b.node), b.matrix);
  SparseMatrix A(map.reduced, map.reduced);
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

SparseMatrix assemble_elements(const ShellModel& m, const DofMap& map,
                               const std::function<Matrix18d(int element)>& element_matrix,
                               const std::vector<NodalBlock>& nodal_blocks) {
  // One pattern workspace per thread: its arrays are sized by the model and
  // reused by every assembly (no allocation churn, docs/benchmarks.md "Allocator").
  thread_local NodeBlockPattern pattern;
  std::vector<int> block_nodes;
  for (const NodalBlock& b : nodal_blocks) block_nodes.push_back(b.node);
  if (!pattern.build(m, map, block_nodes)) return assemble_elements_by_triplets(m, map, element_matrix, nodal_blocks);
  SparseMatrix A(map.reduced, map.reduced);
  A.resizeNonZeros(pattern.nonzeros());
  std::copy(pattern.column_starts().begin(), pattern.column_starts().end(), A.outerIndexPtr());
  std::copy(pattern.rows().begin(), pattern.rows().end(), A.innerIndexPtr());
  // -0.0 + v is v for every v (also -0.0), so each entry ends as the sum the
  // triplets give, term by term in their order.
  double* values = A.valuePtr();
  std::fill(values, values + pattern.nonzeros(), -0.0);
  const int n_elem = static_cast<int>(m.triangles.size());
  for (int e = 0; e < n_elem; ++e) {
    const std::array<int, 3>& t = m.triangles[e];
    if (pattern.plain(t)) {
      pattern.add_plain_element(values, t, element_matrix(e));
    } else {
      add_in_place<18>(values, pattern, map, element_dofs(t), element_matrix(e));
    }
  }
  for (const NodalBlock& b : nodal_blocks) add_in_place<6>(values, pattern, map, node_dofs(b.node), b.matrix);
  return A;
}

SparseMatrix assemble_stiffness(const ShellModel& m, const DofMap& map, const ShellElementOptions& element) {
  return assemble_elements(m, map, [&](int e) {
    const auto& t = m.triangles[e];
    return shell_element_stiffness({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, m.material, element);
  });
}

Eigen::VectorXd assemble_load(const std::vector<NodalLoad>& loads, const DofMap& map, int n_nodes) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map.reduced);
  std::vector<Vector6d> f_full(n_nodes, Vector6d::Zero());
  for (const NodalLoad& load : loads) {
    f_full[load.node].head<3>() += load.force;
    f_full[load.node].tail<3>() += load.moment;
  }
  for (int i = 0; i < n_nodes; ++i)
    for (int d = 0; d < 6; ++d)
      for (int p = map.start[6 * i + d]; p < map.start[6 * i + d + 1]; ++p)
        f(map.index[p]) += map.coef[p] * f_full[i](d);
  return f;
}

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

Eigen::VectorXd symmetric_product(const SparseMatrix& A_lower, const Eigen::VectorXd& x) {
  return A_lower.selfadjointView<Eigen::Lower>() * x;
}

}  // namespace sheetgen
