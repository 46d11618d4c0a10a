#include "sheetgen/fem/lanczos.hpp"

#include <Spectra/SymEigsSolver.h>

#include <algorithm>
#include <string>

#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

// Spectra's operator concept over a std::function.
struct FunctionOp {
  using Scalar = double;
  int n;
  const std::function<void(const double*, double*)>* apply;
  int rows() const { return n; }
  int cols() const { return n; }
  void perform_op(const double* x, double* y) const { (*apply)(x, y); }
};

}  // namespace

LanczosResult largest_eigenpairs(int n, const std::function<void(const double*, double*)>& apply,
                                 const LanczosOptions& options, const char* what) {
  if (options.count < 1 || options.count >= n)
    throw FemError(what, "asks for " + std::to_string(options.count) + " eigenpairs of a " + std::to_string(n) +
                             "-unknown problem (1 to n - 1 are possible)");
  FunctionOp op{n, &apply};
  const int ncv = std::min(n, options.subspace > 0 ? options.subspace : std::max(2 * options.count + 1, 20));
  Spectra::SymEigsSolver<FunctionOp> eigs(op, options.count, std::max(ncv, options.count + 1));
  eigs.init();
  if (options.both_ends && options.count % 2 != 0)
    throw FemError(what, "asks for both ends of the spectrum with an odd count " + std::to_string(options.count));
  const Spectra::SortRule rule = options.both_ends ? Spectra::SortRule::BothEnds : Spectra::SortRule::LargestAlge;
  eigs.compute(rule, options.max_restarts, options.tolerance, Spectra::SortRule::LargestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw FemError(what, "the Lanczos iteration did not converge in " + std::to_string(options.max_restarts) +
                             " restarts (" + std::to_string(eigs.num_operations()) + " operator products)");
  LanczosResult res;
  res.values = eigs.eigenvalues();
  res.vectors = eigs.eigenvectors();
  res.operations = static_cast<int>(eigs.num_operations());
  return res;
}

}  // namespace sheetgen
