#include "sheetgen/fem/stiffness_factor.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/symmetric_amd_ordering.hpp"

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

using EigenLdlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, SymmetricAmdOrdering>;

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


// The load cases side by side, one row per DOF, so that each entry of L is
// read once for every case.
using CaseRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Eigen's sparse triangular solves take a matrix of right-hand sides one
// column at a time, reading the whole factor once per load case; on the
// search's meshes the factor does not fit in the cache, so the six cases read
// it six times from memory. These two read it once. Each case sees Eigen's
// operations in Eigen's order (Eigen/src/SparseCore/TriangularSolver.h, the
// column-major lower and row-major upper solves of a unit triangle), so the
// answer is Eigen's to the last bit; test: StiffnessFactor.SolvesEveryCaseAsEigensLdltDoes.

// X <- L^-1 X, L unit lower triangular and column-major (a stored diagonal is
// ignored). Eigen skips a column whose value is zero, and so does this, case by
// case: subtracting 0 * l can turn a -0 into +0.
void forward_unit_lower(const SparseMatrix& L, CaseRows& X) {
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();
  const Eigen::Index m = X.cols();
  for (Eigen::Index j = 0; j < L.cols(); ++j) {
    const double* xj = X.row(j).data();
    bool every = true, any = false;
    for (Eigen::Index c = 0; c < m; ++c) {
      every = every && xj[c] != 0.0;
      any = any || xj[c] != 0.0;
    }
    if (!any) continue;
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      if (inner[p] <= j) continue;
      double* xi = X.row(inner[p]).data();
      const double l = value[p];
      if (every) {
        for (Eigen::Index c = 0; c < m; ++c) xi[c] -= xj[c] * l;
      } else {
        for (Eigen::Index c = 0; c < m; ++c)
          if (xj[c] != 0.0) xi[c] -= xj[c] * l;
      }
    }
  }
}

// X <- L^-T X for the same L (Eigen's U = L^T, a row-major view of it).
void backward_unit_upper(const SparseMatrix& L, CaseRows& X) {
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();
  const Eigen::Index m = X.cols();
  for (Eigen::Index i = L.cols() - 1; i >= 0; --i) {
    double* xi = X.row(i).data();
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      if (inner[p] <= i) continue;
      const double* xk = X.row(inner[p]).data();
      const double l = value[p];
      for (Eigen::Index c = 0; c < m; ++c) xi[c] -= l * xk[c];
    }
  }
}

}  // namespace

struct StiffnessFactor::Impl {
  // The last pattern, kept to compare exactly (a hash that collided would
  // reuse a wrong elimination order); copied only when the pattern changes.
  Eigen::Index rows = -1;
  std::vector<int> outer, inner;
  ShellSolverBackend backend = ShellSolverBackend::kEigenSimplicialLdlt;
  bool analysed = false;
  int analyses = 0;
  CholmodLlt cholmod;
  EigenLdlt ldlt;
  Eigen::VectorXd inv_sqrt_d;  // D^-1/2 of the LDL^T factor

  bool same_pattern(const SparseMatrix& K) const {
    const Eigen::Index n = K.rows(), nnz = K.nonZeros();
    return analysed && n == rows && nnz == static_cast<Eigen::Index>(inner.size()) &&
           std::equal(outer.begin(), outer.end(), K.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), K.innerIndexPtr());
  }

  void keep_pattern(const SparseMatrix& K) {
    rows = K.rows();
    outer.assign(K.outerIndexPtr(), K.outerIndexPtr() + K.cols() + 1);
    inner.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
  }

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

  Eigen::MatrixXd solve_ldlt(const Eigen::MatrixXd& F) const;
};

StiffnessFactor::StiffnessFactor() : impl_(std::make_unique<Impl>()) {}
StiffnessFactor::~StiffnessFactor() = default;
int StiffnessFactor::symbolic_analyses() const { return impl_->analyses; }
ShellSolverBackend StiffnessFactor::backend() const { return impl_->backend; }

StiffnessFactor::Outcome StiffnessFactor::factorise(const SparseMatrix& K, ShellSolverBackend use,
                                                    double singular_pivot_ratio) {
  Impl& s = *impl_;
  Outcome outcome;
  outcome.pattern_reused = s.backend == use && s.same_pattern(K);
  s.analysed = false;  // until the new factor stands: a failed factor leaves the solver in an unknown state
  const double pivot_ratio = s.factor_numeric(K, use, outcome.pattern_reused);
  if (!(pivot_ratio > singular_pivot_ratio))
    throw FemError("stiffness", "the stiffness matrix is singular (smallest pivot ratio " + str(pivot_ratio) +
                                    "): the supports leave a rigid-body mode or a mechanism free");
  if (!outcome.pattern_reused) {
    s.keep_pattern(K);
    ++s.analyses;
  }
  s.backend = use;
  s.analysed = true;
  return outcome;
}

Eigen::MatrixXd StiffnessFactor::solve(const Eigen::MatrixXd& F) const {
  if (impl_->backend == ShellSolverBackend::kCholmodSupernodal) return impl_->cholmod.solve(F);
  return impl_->solve_ldlt(F);
}

// x = P^T L^-T D^-1 L^-1 P f for every column f of F, as Eigen's
// SimplicialLDLT::solve does it, to the last bit.
Eigen::MatrixXd StiffnessFactor::Impl::solve_ldlt(const Eigen::MatrixXd& F) const {
  const SparseMatrix& L = ldlt.matrixL().nestedExpression();
  if (!L.isCompressed()) return ldlt.solve(F);
  CaseRows X = F;
  if (ldlt.permutationP().size() > 0) X = ldlt.permutationP() * F;
  forward_unit_lower(L, X);
  const Eigen::VectorXd& d = ldlt.vectorD();
  for (Eigen::Index i = 0; i < X.rows(); ++i) X.row(i) *= 1.0 / d(i);  // Eigen: diag(D)^-1 * X
  backward_unit_upper(L, X);
  if (ldlt.permutationP().size() > 0) return ldlt.permutationPinv() * X;
  return X;
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
