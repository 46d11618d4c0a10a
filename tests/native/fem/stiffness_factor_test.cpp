// The factorisation of K_hat (docs/fem.md "Factorisation"): the static cases'
// solve against Eigen's own, and the reuse of the symbolic analysis.
#include "sheetgen/fem/stiffness_factor.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cstring>
#include <vector>

#include "fem_brackets.hpp"
#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/symmetric_amd_ordering.hpp"

namespace sheetgen {
namespace {

struct Assembled {
  SparseMatrix K;
  Eigen::MatrixXd F;  // one column per case
};

// The three-tab bracket's K_hat and six load cases: four dense ones (a force
// on every node), one that loads a single node (its permuted right-hand side
// is zero over most of the forward solve, where the solve skips entries) and
// one that is zero.
Assembled bracket_system() {
  const ShellModel m = test::three_tab_bracket_model(4e-3);
  const DofMap map = build_dof_map(m);
  Assembled a;
  a.K = assemble_stiffness(m, map, ShellElementOptions{});
  const int n = static_cast<int>(m.nodes.size());
  a.F = Eigen::MatrixXd::Zero(map.reduced, 6);
  for (int c = 0; c < 4; ++c) {
    std::vector<NodalLoad> loads;
    for (int i = 0; i < n; ++i)
      loads.push_back(NodalLoad{i, Vec3(std::sin(i + c), std::cos(3.0 * i - c), 0.5 - c), Vec3(0.01 * c, 0, -0.02)});
    a.F.col(c) = assemble_load(loads, map, n);
  }
  a.F.col(4) = assemble_load({NodalLoad{m.load_node, Vec3(0, 0, -60), Vec3::Zero()}}, map, n);
  return a;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(StiffnessFactor, SolvesEveryCaseAsEigensLdltDoes) {
  const Assembled a = bracket_system();
  ASSERT_GT(a.K.rows(), 1000);
  StiffnessFactor factor;
  factor.factorise(a.K, ShellSolverBackend::kEigenSimplicialLdlt, 1e-12);
  const Eigen::MatrixXd ours = factor.solve(a.F);
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> eigen(a.K);
  ASSERT_EQ(eigen.info(), Eigen::Success);
  const Eigen::MatrixXd reference = eigen.solve(a.F);
  ASSERT_EQ(ours.rows(), reference.rows());
  ASSERT_EQ(ours.cols(), reference.cols());
  int differing = 0;
  for (Eigen::Index c = 0; c < ours.cols(); ++c)
    for (Eigen::Index i = 0; i < ours.rows(); ++i) differing += !same_bits(ours(i, c), reference(i, c));
  EXPECT_EQ(differing, 0);
  EXPECT_GT(ours.col(4).norm(), 0.0);
  EXPECT_EQ(ours.col(5).norm(), 0.0);
  // One column alone gives that column of the six, bit for bit.
  const Eigen::MatrixXd single = factor.solve(a.F.col(4));
  for (Eigen::Index i = 0; i < single.rows(); ++i) differing += !same_bits(single(i, 0), ours(i, 4));
  EXPECT_EQ(differing, 0);
}

// The pattern is compared exactly: the same index arrays with new values keep
// the analysis; another numbering of the same matrix (same size, same number
// of entries) does not.
TEST(StiffnessFactor, ReusesTheAnalysisOnlyForTheSamePattern) {
  const Assembled a = bracket_system();
  StiffnessFactor factor;
  EXPECT_FALSE(factor.factorise(a.K, ShellSolverBackend::kEigenSimplicialLdlt, 1e-12).pattern_reused);
  SparseMatrix scaled = 2.0 * a.K;
  EXPECT_TRUE(factor.factorise(scaled, ShellSolverBackend::kEigenSimplicialLdlt, 1e-12).pattern_reused);
  EXPECT_EQ(factor.symbolic_analyses(), 1);
  const Eigen::MatrixXd half = factor.solve(a.F);
  factor.factorise(a.K, ShellSolverBackend::kEigenSimplicialLdlt, 1e-12);
  EXPECT_LT((2.0 * half - factor.solve(a.F)).norm(), 1e-12 * factor.solve(a.F).norm());

  // DOFs 0 and n - 1 swapped: the same SPD matrix renumbered, with as many
  // entries in its lower triangle and other index arrays.
  const int last = static_cast<int>(a.K.rows()) - 1;
  const auto renumber = [last](int i) { return i == 0 ? last : i == last ? 0 : i; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < a.K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a.K, j); it; ++it) {
      const int r = renumber(static_cast<int>(it.row())), c = renumber(static_cast<int>(it.col()));
      entries.emplace_back(std::max(r, c), std::min(r, c), it.value());  // lower triangle
    }
  SparseMatrix moved(a.K.rows(), a.K.cols());
  moved.setFromTriplets(entries.begin(), entries.end());
  ASSERT_EQ(moved.nonZeros(), a.K.nonZeros());
  EXPECT_FALSE(factor.factorise(moved, ShellSolverBackend::kEigenSimplicialLdlt, 1e-12).pattern_reused);
  EXPECT_EQ(factor.symbolic_analyses(), 2);
}

// SimplicialLDLT passes its ordering both triangles of K; on that matrix our
// ordering and Eigen's AMDOrdering give the same elimination order, entry for
// entry (a different one would give other factors, and other rounding).
TEST(SymmetricAmdOrdering, GivesAmdOrderingsPermutation) {
  for (double h : {4e-3, 2.5e-3}) {
    const ShellModel m = test::three_tab_bracket_model(h);
    const SparseMatrix K = assemble_stiffness(m, build_dof_map(m), ShellElementOptions{});
    SparseMatrix full;
    full = K.selfadjointView<Eigen::Lower>();  // as SimplicialCholeskyBase::ordering builds it
    SymmetricAmdOrdering::PermutationType ours, eigen;
    SymmetricAmdOrdering()(full, ours);
    Eigen::AMDOrdering<int>()(full, eigen);
    ASSERT_EQ(ours.size(), K.rows());
    EXPECT_EQ(ours.indices(), eigen.indices());
    int moved = 0;
    for (int i = 0; i < ours.size(); ++i) moved += ours.indices()(i) != i;
    EXPECT_GT(moved, ours.size() / 2);  // an ordering, not the identity
  }
}

}  // namespace
}  // namespace sheetgen
