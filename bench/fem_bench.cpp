// Flat-shell FEM speed (docs/fem.md "Benchmarks"): the three-tab bracket of
// the CalculiX validation test at two mesh sizes (~5 000 and ~20 000 DOF; the
// cold solve also at ~87 000 and ~191 000 DOF, the size of a bay part's final check),
//   BM_FemSolveCold  - a fresh ShellSolver each time: assemble, analyse, factor, solve, stresses;
//   BM_FemSolveWarm  - one ShellSolver, same pattern: the symbolic analysis is reused;
//   BM_FemMesh       - the plate mesher on the same polygons;
//   BM_Ccx           - CalculiX (ccx -i) on the exported deck of the same model, wall time,
//                      with counter speedup = ccx time / our cold time;
//   BM_Ordering      - the fill-reducing ordering of K (0: Eigen's AMDOrdering, 1: SymmetricAmdOrdering);
//   BM_SixCaseSolve  - six load cases on one LDL^T factor (0: Eigen's solve, 1: StiffnessFactor::solve).
// Arguments: {mesh (0: h = 2.5 mm, 1: 1.25 mm; BM_FemSolveCold also 2: 0.625 mm, 3: 0.42 mm),
// backend (0: CHOLMOD, 1: Eigen LDLT, the default)}; BM_Ordering and BM_SixCaseSolve {mesh, variant}.
#include <Eigen/SparseCholesky>
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <string>

// The bracket builders are shared with the CalculiX validation test.
#include "../tests/native/fem/fem_brackets.hpp"
#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/stiffness_factor.hpp"
#include "sheetgen/fem/symmetric_amd_ordering.hpp"

namespace {

using namespace sheetgen;

constexpr double kElementSize[4] = {2.5e-3, 1.25e-3, 0.625e-3, 0.42e-3};  // m -> ~5 600, ~22 000, ~87 000 and ~191 000 DOF

ShellSolveOptions options_for(int backend) {
  ShellSolveOptions o;
  o.backend = backend == 0 ? ShellSolverBackend::kCholmodSupernodal : ShellSolverBackend::kEigenSimplicialLdlt;
  return o;
}

void BM_FemSolveCold(benchmark::State& state) {
  const ShellModel m = test::three_tab_bracket_model(kElementSize[state.range(0)]);
  const ShellSolveOptions o = options_for(static_cast<int>(state.range(1)));
  ShellResult r;
  for (auto _ : state) {
    ShellSolver solver;
    r = solver.solve(m, o);
    benchmark::DoNotOptimize(r.compliance);
  }
  state.counters["dofs"] = r.reduced_dofs;
  state.counters["assemble_ms"] = r.assemble_seconds * 1e3;
  state.counters["factor_ms"] = r.factor_seconds * 1e3;
}

void BM_FemSolveWarm(benchmark::State& state) {
  const ShellModel m = test::three_tab_bracket_model(kElementSize[state.range(0)]);
  const ShellSolveOptions o = options_for(static_cast<int>(state.range(1)));
  ShellSolver solver;
  ShellResult r = solver.solve(m, o);
  for (auto _ : state) {
    r = solver.solve(m, o);
    benchmark::DoNotOptimize(r.compliance);
  }
  state.counters["dofs"] = r.reduced_dofs;
  state.counters["reused"] = r.pattern_reused;
}

void BM_FemMesh(benchmark::State& state) {
  for (auto _ : state) {
    const ShellModel m = test::three_tab_bracket_model(kElementSize[state.range(0)]);
    benchmark::DoNotOptimize(m.triangles.data());
    state.counters["triangles"] = static_cast<double>(m.triangles.size());
  }
}

void BM_Ccx(benchmark::State& state) {
  const ShellModel m = test::three_tab_bracket_model(kElementSize[state.range(0)]);
  std::string dir = (std::filesystem::temp_directory_path() / "sheetgen_bench_ccx_XXXXXX").string();
  if (!mkdtemp(dir.data())) {
    state.SkipWithError("cannot create a temp dir");
    return;
  }
  // Our cold time on the same model, best of 3, for the ratio.
  double ours = 1e30;
  for (int i = 0; i < 3; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    ShellSolver solver;
    benchmark::DoNotOptimize(solver.solve(m).compliance);
    ours = std::min(ours, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  double ccx = 0;
  int runs = 0;
  for (auto _ : state) {
    try {
      const CcxSolution s = solve_with_ccx(m, dir, "bench");
      state.SetIterationTime(s.wall_seconds);
      ccx += s.wall_seconds;
      ++runs;
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
  }
  std::filesystem::remove_all(dir);
  if (runs > 0) {
    state.counters["ours_ms"] = ours * 1e3;
    state.counters["speedup"] = (ccx / runs) / ours;
  }
}

SparseMatrix bracket_stiffness(int mesh) {
  const ShellModel m = test::three_tab_bracket_model(kElementSize[mesh]);
  return assemble_stiffness(m, build_dof_map(m), ShellElementOptions{});
}

void BM_Ordering(benchmark::State& state) {
  const SparseMatrix K = bracket_stiffness(static_cast<int>(state.range(0)));
  SparseMatrix full;
  full = K.selfadjointView<Eigen::Lower>();
  SymmetricAmdOrdering::PermutationType perm;
  for (auto _ : state) {
    if (state.range(1) == 0) {
      Eigen::AMDOrdering<int>()(full, perm);
    } else {
      SymmetricAmdOrdering()(full, perm);
    }
    benchmark::DoNotOptimize(perm.indices().data());
  }
  state.counters["dofs"] = static_cast<double>(K.rows());
}

void BM_SixCaseSolve(benchmark::State& state) {
  const SparseMatrix K = bracket_stiffness(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd F = Eigen::MatrixXd::Random(K.rows(), 6);
  StiffnessFactor ours;
  ours.factorise(K, ShellSolverBackend::kEigenSimplicialLdlt, 1e-12);
  const Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> eigen(K);
  for (auto _ : state) {
    Eigen::MatrixXd U = state.range(1) == 0 ? Eigen::MatrixXd(eigen.solve(F)) : ours.solve(F);
    benchmark::DoNotOptimize(U.data());
  }
  state.counters["dofs"] = static_cast<double>(K.rows());
}

}  // namespace

BENCHMARK(BM_Ordering)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SixCaseSolve)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FemSolveCold)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FemSolveWarm)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FemMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ccx)->Arg(0)->Arg(1)->UseManualTime()->Iterations(2)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
