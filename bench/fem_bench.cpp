// Flat-shell FEM speed (docs/fem.md "Benchmarks"): the three-tab bracket of
// the CalculiX validation test at two mesh sizes (~5 000 and ~20 000 DOF; the
// cold solve also at ~87 000 and ~191 000 DOF, the size of a bay part's final check),
//   BM_FemSolveCold  - a fresh ShellSolver each time: assemble, analyse, factor, solve, stresses;
//   BM_FemSolveWarm  - one ShellSolver, same pattern: the symbolic analysis is reused;
//   BM_FemMesh       - the plate mesher on the same polygons;
//   BM_Ccx           - CalculiX (ccx -i) on the exported deck of the same model, wall time,
//                      with counter speedup = ccx time / our cold time.
// Arguments: {mesh (0: h = 2.5 mm, 1: 1.25 mm; BM_FemSolveCold also 2: 0.625 mm, 3: 0.42 mm),
// backend (0: CHOLMOD, 1: Eigen LDLT, the default)}.
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <string>

// The bracket builders are shared with the CalculiX validation test.
#include "../tests/native/fem/fem_brackets.hpp"
#include "sheetgen/fem/ccx_export.hpp"

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

}  // namespace

BENCHMARK(BM_FemSolveCold)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FemSolveWarm)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FemMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ccx)->Arg(0)->Arg(1)->UseManualTime()->Iterations(2)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
