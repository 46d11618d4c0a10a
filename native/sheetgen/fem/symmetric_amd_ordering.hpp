#pragma once
// The fill-reducing ordering of K_hat's LDL^T factor (internal to the fem area).
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

namespace sheetgen {

// Eigen's AMDOrdering, without its A + A^T. SimplicialLDLT hands its ordering
// the whole symmetric matrix (both triangles, each column sorted), and
// AMDOrdering, written for unsymmetric input too, first adds that matrix to
// its transpose: the same pattern again, built at the cost of a transpose and a
// sparse sum on every new pattern. The approximate minimum degree ordering
// reads only the pattern, in the same order, so the permutation is AMDOrdering's
// (test: SymmetricAmdOrdering.GivesAmdOrderingsPermutation).
struct SymmetricAmdOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  template <typename MatrixType>
  void operator()(const MatrixType& symmetric, PermutationType& perm) const {
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern = symmetric;  // minimum_degree_ordering works in place
    Eigen::internal::minimum_degree_ordering(pattern, perm);
  }
};

}  // namespace sheetgen
