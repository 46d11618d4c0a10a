#include "sheetgen/fem/pencil_modes.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace sheetgen {

std::vector<Vector6d> expand_unit_mode(const DofMap& map, const Eigen::VectorXd& phi, int n_nodes) {
  std::vector<Vector6d> u = expand_displacements(map, phi, n_nodes);
  double largest = 0;
  for (const auto& v : u) largest = std::max(largest, v.head<3>().norm());
  if (largest > 0)
    for (auto& v : u) v /= largest;
  return u;
}

namespace {

// The operator S x = W^-1 B W^-T x of the shift-invert transform, on
// vectors it keeps (no allocation per product).
std::function<void(const double*, double*)> transformed_operator(const StiffnessFactor& factor,
                                                                 const SparseMatrix& B_lower) {
  const int n = static_cast<int>(B_lower.rows());
  return [&factor, &B_lower, n, v = Eigen::VectorXd(n), u = Eigen::VectorXd(n),
          work = Eigen::VectorXd(n)](const double* x, double* y) mutable {
    v = Eigen::Map<const Eigen::VectorXd>(x, n);
    factor.half_solve_transpose(v, work);
    u.setZero();
    u.noalias() += B_lower.selfadjointView<Eigen::Lower>() * v;  // symmetric_product() without its vector
    factor.half_solve(u, work);
    Eigen::Map<Eigen::VectorXd>(y, n) = u;
  };
}

// mu at round-off level (|mu| below 1e-12 of the largest) is no mode: a
// lambda of 1e12 times the first is not a physical load or frequency.
double round_off_floor(const LanczosResult& eig) { return 1e-12 * eig.values.cwiseAbs().maxCoeff(); }

// Appends lambda = 1 / |mu| and phi = W^-T psi scaled to |phi^T B phi| = 1
// (psi is unit, so phi^T B phi = psi^T S psi = mu).
void append_mode(const StiffnessFactor& factor, const Eigen::VectorXd& psi, double mu, PencilModes& out) {
  out.lambdas.push_back(1.0 / std::abs(mu));
  Eigen::VectorXd phi = psi, work;
  factor.half_solve_transpose(phi, work);
  out.modes.push_back(phi / std::sqrt(std::abs(mu)));
}

}  // namespace

PencilModes lowest_positive_modes(const StiffnessFactor& factor, const SparseMatrix& B_lower, int count,
                                  LanczosOptions options, const char* what) {
  const int n = static_cast<int>(B_lower.rows());
  options.count = std::min(count, n - 1);
  const LanczosResult eig = largest_eigenpairs(n, transformed_operator(factor, B_lower), options, what);
  PencilModes out;
  out.operations = eig.operations;
  const double floor = round_off_floor(eig);
  for (int k = 0; k < eig.values.size(); ++k) {
    const double mu = eig.values(k);
    if (!(mu > floor)) break;  // descending: the rest are not positive either
    append_mode(factor, eig.vectors.col(k), mu, out);
  }
  return out;
}

PencilBothSigns lowest_modes_of_both_signs(const StiffnessFactor& factor, const SparseMatrix& B_lower,
                                           LanczosOptions options, const char* what) {
  const int n = static_cast<int>(B_lower.rows());
  options.count = 2;
  options.both_ends = true;
  const LanczosResult eig = largest_eigenpairs(n, transformed_operator(factor, B_lower), options, what);
  PencilBothSigns out;
  out.positive.operations = out.negative.operations = eig.operations;
  const double floor = round_off_floor(eig);
  const int last = static_cast<int>(eig.values.size()) - 1;  // descending: 0 the largest mu, last the smallest
  if (eig.values(0) > floor) append_mode(factor, eig.vectors.col(0), eig.values(0), out.positive);
  if (eig.values(last) < -floor) append_mode(factor, eig.vectors.col(last), eig.values(last), out.negative);
  return out;
}

}  // namespace sheetgen
