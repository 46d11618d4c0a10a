#include "sheetgen/fem/vibration.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/pencil_modes.hpp"
#include "sheetgen/fem/shell_mass.hpp"
#include "sheetgen/fem/shell_solver_impl.hpp"

namespace sheetgen {
namespace {

void check_density(const Material& material) {
  if (!std::isfinite(material.density) || !(material.density > 0)) {
    std::ostringstream s;
    s << "must be a finite number > 0 kg/m^3 for a frequency analysis (got " << material.density << ")";
    throw FemError("material.density", s.str());
  }
}

}  // namespace

VibrationResult analyse_vibration(ShellSolver& solver, const ShellModel& m, const ShellSolveOptions& solve_options,
                                  const VibrationOptions& options) {
  validate_shell_model(m);
  check_density(m.material);
  const auto t0 = std::chrono::steady_clock::now();
  ShellSolveOptions ldlt = solve_options;
  ldlt.backend = ShellSolverBackend::kEigenSimplicialLdlt;
  ShellSolver::Impl& st = solver.state();
  ShellResult timing;
  st.prepare(m, ldlt, timing);

  VibrationResult res;
  std::vector<NodalBlock> bodies;
  for (const PointMass& p : m.point_masses) {
    bodies.push_back(NodalBlock{p.node, rigid_body_mass(p)});
    res.point_mass += p.mass;
  }
  const SparseMatrix M = assemble_elements(
      m, st.map,
      [&](int e) {
        const auto& t = m.triangles[e];
        return shell_element_mass({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}, m.material);
      },
      bodies);
  for (const auto& t : m.triangles)
    res.sheet_mass += m.material.density * m.material.thickness * shell_frame({m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]}).area;

  LanczosOptions lanczos;
  lanczos.tolerance = options.tolerance;
  lanczos.max_restarts = options.max_restarts;
  const PencilModes modes = lowest_positive_modes(st.factor, M, options.modes, lanczos, "vibration");
  res.operations = modes.operations;
  const int n_nodes = static_cast<int>(m.nodes.size());
  for (size_t k = 0; k < modes.lambdas.size(); ++k) {
    res.frequencies_hz.push_back(std::sqrt(modes.lambdas[k]) / (2.0 * M_PI));
    std::vector<Vector6d> u = expand_unit_mode(st.map, modes.modes[k], n_nodes);
    res.mode_shapes.push_back(std::move(u));
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace sheetgen
