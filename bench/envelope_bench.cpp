// The envelope analysis' cost (docs/fem.md "Benchmarks", issue: statics of six
// cases, one buckling factor, three frequencies): the three-tab bracket of
// fem_bench.cpp with a 2 kg box, six inertia cases (9 g forward, 1.5 g
// rearward, 3 g to either side, 6 g down, 3 g up) and its mass, at ~5 000,
// ~22 000 and ~54 000 DOF.
//   BM_Static1     - one case: a fresh ShellSolver (assemble, analyse, factor, solve, stresses);
//   BM_Static6     - the six cases on one factorisation (fresh solver);
//   BM_Buckling    - one buckling factor of the forward case, the factor of K reused;
//   BM_Frequencies - the first three natural frequencies, the factor reused;
//   BM_Envelope    - all of it from a fresh solver: six cases, one buckling factor, three frequencies;
//   BM_CcxEnvelope - CalculiX (ccx -i, S4, its default threads) on the deck export-ccx writes of the
//                    same model: six *STATIC steps, *BUCKLE (1 factor) of the forward case,
//                    *FREQUENCY (3), wall time, with counter ratio = ccx / BM_Envelope's time.
// Argument: mesh (0: h = 2.5 mm, 1: 1.25 mm, 2: 0.8 mm).
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "../tests/native/fem/fem_brackets.hpp"
#include "sheetgen/fem/buckling.hpp"
#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/vibration.hpp"

namespace {

using namespace sheetgen;

constexpr double kElementSize[3] = {2.5e-3, 1.25e-3, 0.8e-3};  // m

// The bracket with six inertia cases of a 2 kg, 30 x 20 x 30 mm box (x
// forward, z up) and the box's mass on its centroid node.
ShellModel envelope_model(int mesh) {
  ShellModel m = test::three_tab_bracket_model(kElementSize[mesh]);
  const double w = 2.0 * 9.80665;  // N per g
  const struct {
    const char* name;
    Vec3 g;
  } factors[6] = {{"forward 9 g", Vec3(9, 0, 0)},  {"rearward 1.5 g", Vec3(-1.5, 0, 0)}, {"left 3 g", Vec3(0, 3, 0)},
                  {"right 3 g", Vec3(0, -3, 0)}, {"down 6 g", Vec3(0, 0, -6)},        {"up 3 g", Vec3(0, 0, 3)}};
  for (const auto& f : factors) m.load_cases.push_back(ShellLoadCase{f.name, {NodalLoad{m.load_node, w * f.g}}});
  PointMass box;
  box.node = m.load_node;
  box.mass = 2.0;
  const Vec3 a(0.03, 0.02, 0.03);  // box edges, m
  box.inertia = (box.mass / 12.0 * Vec3(a.y() * a.y() + a.z() * a.z(), a.x() * a.x() + a.z() * a.z(),
                                        a.x() * a.x() + a.y() * a.y()))
                    .asDiagonal();
  m.point_masses.push_back(box);
  return m;
}

void BM_Static1(benchmark::State& state) {
  const ShellModel m = envelope_model(static_cast<int>(state.range(0)));
  ShellResult r;
  for (auto _ : state) {
    ShellSolver solver;
    r = solver.solve(m);
    benchmark::DoNotOptimize(r.compliance);
  }
  state.counters["dofs"] = r.reduced_dofs;
}

void BM_Static6(benchmark::State& state) {
  const ShellModel m = envelope_model(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    ShellSolver solver;
    benchmark::DoNotOptimize(solver.solve_cases(m).back().compliance);
  }
}

void BM_Buckling(benchmark::State& state) {
  const ShellModel m = envelope_model(static_cast<int>(state.range(0)));
  ShellSolver solver;
  const ShellResult forward = solver.solve_cases(m).front();
  BucklingResult b;
  for (auto _ : state) {
    b = analyse_buckling(solver, m, forward);
    benchmark::DoNotOptimize(b.factors.data());
  }
  state.counters["factor"] = b.factor();
  state.counters["operations"] = b.operations;
}

void BM_Frequencies(benchmark::State& state) {
  const ShellModel m = envelope_model(static_cast<int>(state.range(0)));
  ShellSolver solver;
  solver.solve_cases(m);
  VibrationResult v;
  for (auto _ : state) {
    v = analyse_vibration(solver, m);
    benchmark::DoNotOptimize(v.frequencies_hz.data());
  }
  state.counters["f1_hz"] = v.frequencies_hz.front();
  state.counters["operations"] = v.operations;
}

void BM_Envelope(benchmark::State& state) {
  const ShellModel m = envelope_model(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    ShellSolver solver;
    const std::vector<ShellResult> cases = solver.solve_cases(m);
    benchmark::DoNotOptimize(analyse_buckling(solver, m, cases.front()).factors.data());
    benchmark::DoNotOptimize(analyse_vibration(solver, m).frequencies_hz.data());
  }
}

// Our whole envelope, one fresh solver, seconds.
double envelope_seconds(const ShellModel& m) {
  const auto t0 = std::chrono::steady_clock::now();
  ShellSolver solver;
  const std::vector<ShellResult> cases = solver.solve_cases(m);
  benchmark::DoNotOptimize(analyse_buckling(solver, m, cases.front()).factors.data());
  benchmark::DoNotOptimize(analyse_vibration(solver, m).frequencies_hz.data());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void BM_CcxEnvelope(benchmark::State& state) {
  const ShellModel m = envelope_model(static_cast<int>(state.range(0)));
  std::string dir = (std::filesystem::temp_directory_path() / "sheetgen_bench_env_XXXXXX").string();
  if (!mkdtemp(dir.data())) {
    state.SkipWithError("cannot create a temp dir");
    return;
  }
  CcxExportOptions o;
  o.buckle_case = 0;
  o.buckling_factors = 1;
  o.frequency_modes = 3;
  const double ours = envelope_seconds(m);
  double ccx = 0;
  CcxEnvelope e;
  for (auto _ : state) {
    try {
      e = solve_envelope_with_ccx(m, dir, "bench", "ccx", o);
    } catch (const std::exception& ex) {
      state.SkipWithError(ex.what());
      break;
    }
    state.SetIterationTime(e.wall_seconds);
    ccx = e.wall_seconds;
  }
  std::filesystem::remove_all(dir);
  if (ccx > 0) {
    state.counters["ours_ms"] = ours * 1e3;
    state.counters["ratio"] = ccx / ours;
    state.counters["ccx_buckling"] = e.buckling_factors.front();
    state.counters["ccx_f1_hz"] = e.frequencies_hz.front();
  }
}

}  // namespace

BENCHMARK(BM_Static1)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Static6)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Buckling)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Frequencies)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Envelope)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CcxEnvelope)->DenseRange(0, 2)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
