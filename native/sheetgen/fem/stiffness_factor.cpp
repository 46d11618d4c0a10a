#include "sheetgen/fem/stiffness_factor.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <limits>
#include <sstream>

#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
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


}  // namespace

struct StiffnessFactor::Impl {
  std::uint64_t pattern = 0, values = 0;
  ShellSolverBackend backend = ShellSolverBackend::kEigenSimplicialLdlt;
  bool analysed = false, factored = false;
  int analyses = 0;
  CholmodLlt cholmod;
  EigenLdlt ldlt;
  Eigen::VectorXd inv_sqrt_d;  // D^-1/2 of the LDL^T factor

  // The numeric factor; returns the smallest pivot ratio (0 when it failed).
  double factor_numeric(const SparseMatrix& K, ShellSolverBackend use, bool reuse_pattern) {
    const Eigen::VectorXd diag = K.diagonal();
    if (use == ShellSolverBackend::kCholmodSupernodal) {
      if (!reuse_pattern) cholmod.analyzePattern(K);
      cholmod.factorize(K);
      return cholmod.info() == Eigen::Success ? cholmod.min_pivot_ratio(diag) : 0.0;
    }
    if (!reuse_pattern) ldlt.analyzePattern(K);
    ldlt.factorize(K);
    if (ldlt.info() != Eigen::Success) return 0.0;
    const double ratio = min_pivot_ratio(ldlt, diag);
    if (ratio > 0) inv_sqrt_d = ldlt.vectorD().cwiseSqrt().cwiseInverse();
    return ratio;
  }
};

StiffnessFactor::StiffnessFactor() : impl_(std::make_unique<Impl>()) {}
StiffnessFactor::~StiffnessFactor() = default;
int StiffnessFactor::symbolic_analyses() const { return impl_->analyses; }
ShellSolverBackend StiffnessFactor::backend() const { return impl_->backend; }

StiffnessFactor::Outcome StiffnessFactor::factorise(const SparseMatrix& K, ShellSolverBackend use,
                                                    double singular_pivot_ratio) {
  Impl& s = *impl_;
  const std::uint64_t pattern = pattern_hash(K);
  const std::uint64_t values = value_hash(K);
  Outcome outcome;
  outcome.pattern_reused = s.analysed && s.pattern == pattern && s.backend == use;
  outcome.factor_reused = outcome.pattern_reused && s.factored && s.values == values;
  if (outcome.factor_reused) return outcome;
  s.factored = false;
  const double pivot_ratio = s.factor_numeric(K, use, outcome.pattern_reused);
  s.analysed = true;
  s.pattern = pattern;
  s.backend = use;
  if (!outcome.pattern_reused) ++s.analyses;
  if (!(pivot_ratio > singular_pivot_ratio)) {
    s.analysed = false;  // a failed factor leaves the solver in an unknown state
    throw FemError("stiffness", "the stiffness matrix is singular (smallest pivot ratio " + str(pivot_ratio) +
                                    "): the supports leave a rigid-body mode or a mechanism free");
  }
  s.values = values;
  s.factored = true;
  return outcome;
}

Eigen::MatrixXd StiffnessFactor::solve(const Eigen::MatrixXd& F) const {
  if (impl_->backend == ShellSolverBackend::kCholmodSupernodal) return impl_->cholmod.solve(F);
  return impl_->ldlt.solve(F);
}

void StiffnessFactor::half_solve(Eigen::VectorXd& x, Eigen::VectorXd& work) const {
  const Impl& s = *impl_;
  work.resize(x.size());
  work.noalias() = s.ldlt.permutationP() * x;
  s.ldlt.matrixL().solveInPlace(work);
  x = work.cwiseProduct(s.inv_sqrt_d);
}

void StiffnessFactor::half_solve_transpose(Eigen::VectorXd& y, Eigen::VectorXd& work) const {
  const Impl& s = *impl_;
  work = y.cwiseProduct(s.inv_sqrt_d);
  s.ldlt.matrixU().solveInPlace(work);
  y.noalias() = s.ldlt.permutationPinv() * work;
}

}  // namespace sheetgen
