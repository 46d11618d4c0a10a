#pragma once
// The sparsity pattern of a reduced matrix T^T A T (lower triangle) built node
// block by node block, and the position of each entry in it (internal to the
// fem area). assemble_elements() scatters element matrices straight into it.
//
// Why: building the matrix from a triplet list (Eigen's setFromTriplets)
// writes 171 triplets per element and sorts them by a transpose, all of it
// cache misses; that was 15 % of a bay solve (docs/benchmarks.md "Where the
// time goes"). Here the pattern comes from the node graph (a few pairs per
// element) and the values are added in place, in the triplets' order, so the
// matrix is the same to the last bit.
#include <array>
#include <vector>

#include "sheetgen/fem/shell_assembly.hpp"

namespace sheetgen {

// A node that owns reduced DOFs owns a contiguous range of them (build_dof_map
// numbers them node by node). A column of node q's range holds, in row order,
// the rest of q's diagonal block, then the whole range of each neighbour p of
// q with a later range (a node sharing an element with q, through the map).
class NodeBlockPattern {
 public:
  // Builds the pattern of the elements of `m` and of single-node blocks on
  // `block_nodes`, through `map`. False when the map is not node-blocked
  // (some node's DOFs do not name every reduced DOF of the nodes they name):
  // then this pattern would hold entries the triplets do not, and the caller
  // assembles through triplets.
  bool build(const ShellModel& m, const DofMap& map, const std::vector<int>& block_nodes);

  int nonzeros() const { return col_start_.empty() ? 0 : col_start_.back(); }
  const std::vector<int>& column_starts() const { return col_start_; }  // #reduced + 1
  const std::vector<int>& rows() const { return rows_; }                // #nonzeros, by column

  // The owners (nodes) of the reduced DOFs named by `full_dofs` (full DOF ids)
  // and the row offset of each owner pair: what position() needs for one
  // element or nodal block.
  void begin_block(const DofMap& map, const int* full_dofs, int count);
  // Position in rows()/values of entry (ia, ib), ia >= ib, both named by the
  // full DOFs of the last begin_block().
  int position(int ia, int ib) const {
    const int p = owner_[ia], q = owner_[ib];
    if (p == q) return col_start_[ib] + (ia - ib);
    return col_start_[ib] + (first_[q] + count_[q] - ib) + block_offset_[local_[p]][local_[q]] + (ia - first_[p]);
  }

  // A triangle whose three nodes are plain: each full DOF names at most one
  // reduced DOF, its node's own, with coefficient 1 (no rigid-link slave).
  bool plain(const std::array<int, 3>& t) const { return plain_[t[0]] && plain_[t[1]] && plain_[t[2]]; }
  // Adds a plain triangle's lower-triangle terms into `values`, node pair by
  // node pair: what add_in_place() adds through begin_block() and position(),
  // term for term (1 * 1 * A(a, b) is A(a, b), and a plain triangle puts one
  // term on each entry), without looking each term's DOFs up in the map.
  void add_plain_element(double* values, const std::array<int, 3>& t, const Matrix18d& A) const;

 private:
  static constexpr int kMaxOwners = 8;  // of one element; more falls back to triplets
  bool owners_cover_their_dofs(const DofMap& map, int n_nodes);
  void find_plain_nodes(const DofMap& map, int n_nodes);
  int pair_offset(int p, int q) const;
  int element_owners(const DofMap& map, const int* full_dofs, int count, int* owners) const;
  bool collect_neighbours(const ShellModel& m, const DofMap& map, const std::vector<int>& block_nodes);
  void lay_out_columns(int reduced);

  std::vector<int> owner_;          // reduced DOF -> node
  std::vector<int> first_, count_;  // node -> its first reduced DOF, how many (0: none)
  std::vector<char> has_diagonal_;  // node -> named by some element or block
  std::vector<int> adj_start_;      // node -> CSR offset into adj_ / adj_rows_ (#nodes + 1)
  std::vector<int> adj_;            // later neighbours of each node, ascending
  std::vector<int> adj_rows_;       // rows of the neighbours before it, in the node's columns
  std::vector<int> col_start_, rows_;
  std::vector<char> plain_;         // node -> plain (see plain())
  std::vector<int> reduced_of_;     // full DOF of a plain node -> its reduced DOF, -1 when fixed
  std::vector<std::pair<int, int>> pairs_;  // (node, later neighbour) before sorting
  // The last begin_block(): node -> index among its owners, and their offsets.
  std::vector<int> local_;
  int block_offset_[kMaxOwners][kMaxOwners] = {};
};

}  // namespace sheetgen
