#include "sheetgen/fem/pencil_modes.hpp"

#include <algorithm>
#include <cmath>

namespace sheetgen {

std::vector<Vector6d> expand_unit_mode(const DofMap& map, const Eigen::VectorXd& phi, int n_nodes) {
  std::vector<Vector6d> u = expand_displacements(map, phi, n_nodes);
  double largest = 0;
  for (const auto& v : u) largest = std::max(largest, v.head<3>().norm());
  if (largest > 0)
    for (auto& v : u) v /= largest;
  return u;
}

PencilModes lowest_positive_modes(const StiffnessFactor& factor, const SparseMatrix& B_lower, int count,
                                  LanczosOptions options, const char* what) {
  const int n = static_cast<int>(B_lower.rows());
  auto apply = [&](const double* x, double* y) {
    const Eigen::VectorXd v = factor.half_solve_transpose(Eigen::Map<const Eigen::VectorXd>(x, n));
    Eigen::Map<Eigen::VectorXd>(y, n) = factor.half_solve(symmetric_product(B_lower, v));
  };
  options.count = std::min(count, n - 1);
  const LanczosResult eig = largest_eigenpairs(n, apply, options, what);
  PencilModes out;
  out.operations = eig.operations;
  // mu at round-off level (|mu| below 1e-12 of the largest) is no mode: a
  // lambda of 1e12 times the first is not a physical load or frequency.
  const double floor = 1e-12 * eig.values.cwiseAbs().maxCoeff();
  for (int k = 0; k < eig.values.size(); ++k) {
    const double mu = eig.values(k);
    if (!(mu > floor)) break;  // descending: the rest are not positive either
    out.lambdas.push_back(1.0 / mu);
    // psi is unit, so phi^T B phi = psi^T S psi = mu; scale phi to 1.
    out.modes.push_back(factor.half_solve_transpose(eig.vectors.col(k)) / std::sqrt(mu));
  }
  return out;
}

}  // namespace sheetgen
