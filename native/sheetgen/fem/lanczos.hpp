#pragma once
// The largest eigenpairs of a symmetric operator by implicitly restarted
// Lanczos: the one door to Spectra (libspectra-dev, on Eigen). Buckling and
// vibration hand it K's shift-invert transform (docs/fem.md "Eigenproblems").
#include <Eigen/Core>
#include <functional>

namespace sheetgen {

struct LanczosOptions {
  int count = 1;             // eigenpairs wanted
  int subspace = 0;          // Lanczos vectors; <= 0: max(2 count + 1, 20), at most n
  // Relative residual of each Ritz value. The eigenvalue's own error is of the
  // order of the residual squared over the gap to the next one (symmetric
  // operator), so 1e-6 gives the bay's buckling factors and frequencies to 14
  // digits of what 1e-9 gives, with a quarter fewer operator products
  // (docs/fem.md "Eigenproblems").
  double tolerance = 1e-6;
  int max_restarts = 500;
  // Both ends of the spectrum: count / 2 of the largest and count / 2 of the
  // smallest algebraic eigenvalues (count even). One pencil of a buckling
  // case then answers for the case and its opposite (docs/fem.md
  // "Envelope analysis").
  bool both_ends = false;
};

struct LanczosResult {
  Eigen::VectorXd values;   // the `count` largest algebraic eigenvalues (or both ends), descending
  Eigen::MatrixXd vectors;  // n x count, unit columns
  int operations = 0;       // operator applications
};

// `apply(x, y)` sets y = A x for vectors of length n. Throws FemError when the
// iteration does not converge (named `what`, e.g. "buckling").
LanczosResult largest_eigenpairs(int n, const std::function<void(const double* x, double* y)>& apply,
                                 const LanczosOptions& options, const char* what);

}  // namespace sheetgen
