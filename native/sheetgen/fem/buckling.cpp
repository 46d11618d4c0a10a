#include "sheetgen/fem/buckling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/geometric_stiffness.hpp"
#include "sheetgen/fem/pencil_modes.hpp"
#include "sheetgen/fem/shell_solver_impl.hpp"

namespace sheetgen {
namespace {

// Per element, the membrane stress resultants (Nxx, Nyy, Nxy), N/m, local frame.
std::vector<Eigen::Vector3d> membrane_resultants(const ShellModel& m, const ShellResult& ref,
                                                 const ShellElementOptions& element) {
  std::vector<Eigen::Vector3d> N(m.triangles.size());
  for (size_t e = 0; e < m.triangles.size(); ++e) {
    const auto& t = m.triangles[e];
    Vector18d ue;
    for (int k = 0; k < 3; ++k) ue.segment<6>(6 * k) = ref.displacements[t[k]];
    const ShellStressOperator op =
        shell_stress_operator({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, m.material, element, false);
    N[e] = membrane_stress(op, ue) * m.material.thickness;
  }
  return N;
}

// Smaller and larger principal value of (Nxx, Nyy, Nxy).
std::pair<double, double> principal(const Eigen::Vector3d& n) {
  const double c = 0.5 * (n(0) + n(1));
  const double r = std::hypot(0.5 * (n(0) - n(1)), n(2));
  return {c - r, c + r};
}

// Whether the field N, and the opposite field -N, compress part of the sheet:
// some element's smaller principal resultant below -threshold times the
// largest principal magnitude (for -N the smaller principal is -hi).
struct Compression {
  bool under_load = false;
  bool under_opposite = false;
};
Compression compression(const std::vector<Eigen::Vector3d>& N, double threshold) {
  double largest = 0, lowest = 0, highest = 0;
  for (const auto& n : N) {
    const auto [lo, hi] = principal(n);
    largest = std::max({largest, std::abs(lo), std::abs(hi)});
    lowest = std::min(lowest, lo);
    highest = std::max(highest, hi);
  }
  if (!(largest > 0)) return {};
  return {lowest < -threshold * largest, highest > threshold * largest};
}

void check_reference(const ShellModel& m, const ShellResult& ref) {
  validate_shell_model(m);
  if (ref.displacements.size() != m.nodes.size())
    throw FemError("buckling reference", "holds " + std::to_string(ref.displacements.size()) +
                                             " nodal displacements for a model of " + std::to_string(m.nodes.size()) +
                                             " nodes (not a static result of this model)");
}

// B = -K_G of the resultants N, on the solver's factor of K (LDL^T backend:
// the transform needs its D), assembled in the factor's DOF order.
SparseMatrix prepare_pencil(ShellSolver& solver, const ShellModel& m, const std::vector<Eigen::Vector3d>& N,
                            const ShellSolveOptions& solve_options) {
  ShellSolveOptions ldlt = solve_options;
  ldlt.backend = ShellSolverBackend::kEigenSimplicialLdlt;
  ShellSolver::Impl& st = solver.state();
  ShellResult timing;
  st.prepare(m, ldlt, timing);
  return assemble_elements(m, st.map, [&](int e) {
    const auto& t = m.triangles[e];
    return Matrix18d(-shell_geometric_stiffness({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, N[e]));
  });
}

LanczosOptions lanczos_options(const BucklingOptions& options) {
  LanczosOptions lanczos;
  lanczos.tolerance = options.tolerance;
  lanczos.max_restarts = options.max_restarts;
  return lanczos;
}

void take_modes(const PencilModes& modes, const DofMap& map, int n_nodes, BucklingResult& res) {
  res.factors = modes.lambdas;
  res.operations = modes.operations;
  for (const Eigen::VectorXd& phi : modes.modes) res.mode_shapes.push_back(expand_unit_mode(map, phi, n_nodes));
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

BucklingResult analyse_buckling(ShellSolver& solver, const ShellModel& m, const ShellResult& ref,
                                const ShellSolveOptions& solve_options, const BucklingOptions& options) {
  check_reference(m, ref);
  const auto t0 = std::chrono::steady_clock::now();
  BucklingResult res;
  res.case_name = ref.case_name;
  const std::vector<Eigen::Vector3d> N = membrane_resultants(m, ref, solve_options.element);
  res.compressed = compression(N, options.compression_threshold).under_load;
  if (res.compressed) {
    const SparseMatrix B = prepare_pencil(solver, m, N, solve_options);
    const ShellSolver::Impl& st = solver.state();
    take_modes(lowest_positive_modes(st.factor, B, options.modes, lanczos_options(options), "buckling"), st.map,
               static_cast<int>(m.nodes.size()), res);
  }
  res.seconds = seconds_since(t0);
  return res;
}

BucklingPair analyse_buckling_both_ways(ShellSolver& solver, const ShellModel& m, const ShellResult& ref,
                                        const ShellSolveOptions& solve_options, const BucklingOptions& options) {
  check_reference(m, ref);
  const auto t0 = std::chrono::steady_clock::now();
  BucklingPair out;
  out.first.case_name = ref.case_name;
  const std::vector<Eigen::Vector3d> N = membrane_resultants(m, ref, solve_options.element);
  const Compression c = compression(N, options.compression_threshold);
  out.first.compressed = c.under_load;
  out.second.compressed = c.under_opposite;
  if (out.first.compressed || out.second.compressed) {
    const SparseMatrix B = prepare_pencil(solver, m, N, solve_options);
    const ShellSolver::Impl& st = solver.state();
    const int n_nodes = static_cast<int>(m.nodes.size());
    const PencilBothSigns modes = lowest_modes_of_both_signs(st.factor, B, lanczos_options(options), "buckling");
    // A side that compresses nothing cannot buckle (as analyse_buckling): its
    // eigenvalue, if any, is not a buckling load.
    if (out.first.compressed) take_modes(modes.positive, st.map, n_nodes, out.first);
    if (out.second.compressed) take_modes(modes.negative, st.map, n_nodes, out.second);
  }
  out.first.seconds = out.second.seconds = seconds_since(t0);
  return out;
}

}  // namespace sheetgen
