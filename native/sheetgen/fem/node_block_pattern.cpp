#include "sheetgen/fem/node_block_pattern.hpp"

#include <algorithm>

namespace sheetgen {

bool NodeBlockPattern::build(const ShellModel& m, const DofMap& map, const std::vector<int>& block_nodes) {
  const int n_nodes = static_cast<int>(m.nodes.size());
  owner_ = map.owner;
  first_.assign(n_nodes, -1);
  count_.assign(n_nodes, 0);
  for (int r = 0; r < map.reduced; ++r) {
    const int p = owner_[r];
    if (first_[p] < 0) first_[p] = r;
    ++count_[p];
  }
  if (!owners_cover_their_dofs(map, n_nodes)) return false;
  local_.assign(n_nodes, 0);
  pairs_.clear();
  has_diagonal_.assign(n_nodes, 0);
  if (!collect_neighbours(m, map, block_nodes)) return false;
  lay_out_columns(map.reduced);
  find_plain_nodes(map, n_nodes);
  return true;
}

void NodeBlockPattern::find_plain_nodes(const DofMap& map, int n_nodes) {
  plain_.assign(n_nodes, 1);
  reduced_of_.assign(6 * static_cast<size_t>(n_nodes), -1);
  for (int i = 0; i < n_nodes; ++i)
    for (int d = 0; d < 6; ++d) {
      const int dof = 6 * i + d, begin = map.start[dof], end = map.start[dof + 1];
      if (end == begin) continue;  // fixed
      if (end - begin > 1 || owner_[map.index[begin]] != i || map.coef[begin] != 1.0) plain_[i] = 0;
      reduced_of_[dof] = map.index[begin];
    }
}

// The row offset of node p's range in the columns of node q (q < p, both
// with reduced DOFs and neighbours in the pattern).
int NodeBlockPattern::pair_offset(int p, int q) const {
  const auto beg = adj_.begin() + adj_start_[q];
  const auto at = std::lower_bound(beg, adj_.begin() + adj_start_[q + 1], p);
  return adj_rows_[adj_start_[q] + static_cast<int>(at - beg)];
}

void NodeBlockPattern::add_plain_element(double* values, const std::array<int, 3>& t, const Matrix18d& A) const {
  for (int lb = 0; lb < 3; ++lb) {    // the column's node
    const int q = t[lb];
    if (count_[q] == 0) continue;
    for (int la = 0; la < 3; ++la) {  // the row's node
      const int p = t[la];
      if (count_[p] == 0 || p < q) continue;  // lower triangle: p's range is not before q's
      const int offset = p == q ? 0 : pair_offset(p, q) - first_[p];
      for (int db = 0; db < 6; ++db) {
        const int ib = reduced_of_[6 * q + db];
        if (ib < 0) continue;
        // Column ib: its diagonal block's rest from ib, then q's neighbours' ranges.
        double* column = values + col_start_[ib] + (p == q ? -ib : first_[q] + count_[q] - ib + offset);
        for (int da = 0; da < 6; ++da) {
          const int ia = reduced_of_[6 * p + da];
          if (ia < 0 || ia < ib) continue;
          column[ia] += A(6 * la + da, 6 * lb + db);
        }
      }
    }
  }
}

// Node-blocked: the entries of every node's six DOFs name, for each node
// they name, every reduced DOF of that node (a free node names its own, a
// rigid link's slave all of its master's). Then an element's triplets fill
// whole blocks of its nodes' ranges, which is what this pattern holds.
bool NodeBlockPattern::owners_cover_their_dofs(const DofMap& map, int n_nodes) {
  for (int i = 0; i < n_nodes; ++i) {
    int owners[kMaxOwners], masks[kMaxOwners], n = 0;
    for (int p = map.start[6 * i]; p < map.start[6 * i + 6]; ++p) {
      const int r = map.index[p], o = owner_[r];
      int k = 0;
      while (k < n && owners[k] != o) ++k;
      if (k == n) {
        if (n == kMaxOwners) return false;
        owners[n] = o;
        masks[n++] = 0;
      }
      masks[k] |= 1 << (r - first_[o]);
    }
    for (int k = 0; k < n; ++k)
      if (masks[k] != (1 << count_[owners[k]]) - 1) return false;
  }
  return true;
}

// The distinct owners of the reduced DOFs named by `full_dofs`; -1 when more
// than kMaxOwners.
int NodeBlockPattern::element_owners(const DofMap& map, const int* full_dofs, int count, int* owners) const {
  int n = 0;
  for (int a = 0; a < count; ++a)
    for (int p = map.start[full_dofs[a]]; p < map.start[full_dofs[a] + 1]; ++p) {
      const int o = owner_[map.index[p]];
      int k = 0;
      while (k < n && owners[k] != o) ++k;
      if (k < n) continue;
      if (n == kMaxOwners) return -1;
      owners[n++] = o;
    }
  return n;
}

// pairs_ <- every (node, later neighbour) once, sorted; false when an
// element names more than kMaxOwners nodes.
bool NodeBlockPattern::collect_neighbours(const ShellModel& m, const DofMap& map, const std::vector<int>& block_nodes) {
  auto add_block = [&](const int* dofs, int count) {
    int owners[kMaxOwners];
    const int n = element_owners(map, dofs, count, owners);
    if (n < 0) return false;
    for (int a = 0; a < n; ++a) {
      has_diagonal_[owners[a]] = 1;
      for (int b = 0; b < n; ++b)
        if (owners[a] < owners[b]) pairs_.emplace_back(owners[a], owners[b]);
    }
    return true;
  };
  for (const auto& t : m.triangles)
    if (!add_block(element_dofs(t).data(), 18)) return false;
  for (int node : block_nodes)
    if (!add_block(node_dofs(node).data(), 6)) return false;
  std::sort(pairs_.begin(), pairs_.end());
  pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
  return true;
}

// Column starts and rows from the neighbour lists, node range by node range
// (rows ascend in every column: the diagonal block's rest, then each later
// neighbour's range in node order, which is DOF order).
void NodeBlockPattern::lay_out_columns(int reduced) {
  const int n_nodes = static_cast<int>(first_.size());
  adj_start_.assign(n_nodes + 1, 0);
  for (const auto& pq : pairs_) ++adj_start_[pq.first + 1];
  for (int i = 0; i < n_nodes; ++i) adj_start_[i + 1] += adj_start_[i];
  adj_.resize(pairs_.size());
  adj_rows_.resize(pairs_.size());
  for (size_t k = 0; k < pairs_.size(); ++k) adj_[k] = pairs_[k].second;  // sorted by node, then neighbour
  col_start_.assign(reduced + 1, 0);
  for (int q = 0; q < n_nodes; ++q) {
    int rows = 0;
    for (int k = adj_start_[q]; k < adj_start_[q + 1]; ++k) {
      adj_rows_[k] = rows;
      rows += count_[adj_[k]];
    }
    if (!has_diagonal_[q]) continue;  // no element names it: empty columns, as the triplets leave them
    for (int k = 0; k < count_[q]; ++k) col_start_[first_[q] + k + 1] = (count_[q] - k) + rows;
  }
  for (int c = 0; c < reduced; ++c) col_start_[c + 1] += col_start_[c];
  rows_.resize(col_start_[reduced]);
  for (int q = 0; q < n_nodes; ++q) {
    if (!has_diagonal_[q]) continue;
    for (int k = 0; k < count_[q]; ++k) {
      const int c = first_[q] + k;
      int* out = &rows_[col_start_[c]];
      for (int r = c; r < first_[q] + count_[q]; ++r) *out++ = r;
      for (int j = adj_start_[q]; j < adj_start_[q + 1]; ++j)
        for (int r = 0; r < count_[adj_[j]]; ++r) *out++ = first_[adj_[j]] + r;
    }
  }
}

void NodeBlockPattern::begin_block(const DofMap& map, const int* full_dofs, int count) {
  int owners[kMaxOwners];
  const int n = element_owners(map, full_dofs, count, owners);  // build() saw every block: n >= 0
  for (int a = 0; a < n; ++a) local_[owners[a]] = a;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int p = owners[a], q = owners[b];
      if (!(q < p)) continue;
      const auto beg = adj_.begin() + adj_start_[q];
      const auto at = std::lower_bound(beg, adj_.begin() + adj_start_[q + 1], p);
      block_offset_[a][b] = adj_rows_[adj_start_[q] + static_cast<int>(at - beg)];
    }
}

}  // namespace sheetgen
