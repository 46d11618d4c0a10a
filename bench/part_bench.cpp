// Part grammar throughput (docs/manufacturing.md "Performance"): realisation
// and validity of a 20-tab part, the numbers the discovery search lives on
// (goal: >= 20 000 realisations/s, >= 2 000 full validity checks/s), plus the
// once-per-result manufacturing plan (unfold + overlap, bend sequence).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/press_brake.hpp"
#include "sheetgen/part/validity.hpp"
#include "../tests/native/common/scene_fixture.hpp"

namespace {

using namespace sheetgen;
const double kDeg = M_PI / 180.0;

using testing_scenes::rectangle;

// Scene: a 120 x 120 x 40 mm load whose base tab is at z = 0, a floor 200 mm
// below, a wall at x = 300 mm. Defaults of docs/architecture.md for t = 1.6 mm.
Problem scene() {
  Problem p;
  p.source = "<bench>";
  Manufacturing& m = p.manufacturing;
  m.bend_radius = 6.4e-3;
  m.min_flange = 12.8e-3;
  m.min_tab_width = 16e-3;
  m.min_tab_length = 16e-3;
  m.rivet_diameter = 3.96875e-3;
  m.rivet_edge_distance = 2 * m.rivet_diameter;
  m.rivet_pitch = 6 * m.rivet_diameter;
  Load load;
  load.name = "box";
  load.center = Vec3(0.06, 0.06, 0.0208);
  load.size = Vec3(0.12, 0.12, 0.04);
  p.loads.push_back(load);
  p.meshes.push_back({"floor", rectangle(-0.3, 0.4, -0.3, 0.4, -0.2), "<inline>"});
  TriangleMesh wall;
  wall.vertices = {Vec3(0.3, -0.3, -0.2), Vec3(0.3, 0.4, -0.2), Vec3(0.3, 0.4, 0.1), Vec3(0.3, -0.3, 0.1)};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  p.meshes.push_back({"wall", wall, "<inline>"});
  return p;
}

// 20 tabs: on every base edge two walls bent down 90 deg (30 mm), each with an
// outward flange (+90 deg, 20 mm); the first flange per edge carries a lip bent
// -60 deg (16 mm).
Part twenty_tabs(const Problem& p) {
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  for (int e = 0; e < 4; ++e) {
    for (int k = 0; k < 2; ++k) {
      const int wall = part.add_tab(0, e, {k == 0 ? 0.015 : 0.075, 0.03, 0.03, 0, 0, -90 * kDeg});
      const int flange = part.add_tab(wall, kFarEdge, {0.005, 0.02, 0.02, 0, 0, 90 * kDeg});
      if (k == 0) part.add_tab(flange, kFarEdge, {0.002, 0.016, 0.016, 0, 0, -60 * kDeg});
    }
  }
  return part;
}

struct Fixture {
  Problem problem = scene();
  Part part = twenty_tabs(problem);
  SheetSpec spec = SheetSpec::from(problem);
  std::unique_ptr<Environment> env;
  Environment& environment() {
    if (!env) env = std::make_unique<Environment>(problem);
    return *env;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_Realise(benchmark::State& state) {
  Fixture& f = fixture();
  RealisedPart rp;
  for (auto _ : state) {
    realise_into(f.part, rp);
    benchmark::DoNotOptimize(rp.tabs.back().corners[2]);
  }
  state.counters["tabs"] = f.part.size() - 1;
  state.counters["realisations/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Realise);

void BM_ValidityGeometric(benchmark::State& state) {  // limits + self-intersection, no environment
  Fixture& f = fixture();
  RealisedPart rp;
  for (auto _ : state) {
    realise_into(f.part, rp);
    const ValidityReport r = check_validity(f.part, rp, f.spec);
    if (!r.valid()) state.SkipWithError(r.summary().c_str());
  }
  state.counters["checks/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ValidityGeometric);

void BM_ValidityFull(benchmark::State& state) {  // realise + limits + self-intersection + environment
  Fixture& f = fixture();
  Environment& env = f.environment();
  RealisedPart rp;
  for (auto _ : state) {
    realise_into(f.part, rp);
    const ValidityReport r = check_validity(f.part, rp, env);
    if (!r.valid()) state.SkipWithError(r.summary().c_str());
  }
  state.counters["checks/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ValidityFull);

void BM_UnfoldAndOverlap(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    const FlatPattern flat = unfold(f.part, f.spec);
    const ValidityReport r = check_flat_pattern(flat, f.spec);
    if (!flat.ok() || !r.valid()) state.SkipWithError("flat pattern of the bench part is not valid");
    benchmark::DoNotOptimize(flat.outline.data());
  }
}
BENCHMARK(BM_UnfoldAndOverlap);

// Argument: 1 skips the states provably clear (the default), 0 checks every state.
void BM_BendSequencePlan(benchmark::State& state) {
  Fixture& f = fixture();
  BendSequenceOptions o;
  o.skip_clear_states = state.range(0) != 0;
  int sweeps = 0;
  for (auto _ : state) {
    const BendSequenceResult r = plan_bend_sequence(f.part, f.spec, o);
    if (!r.ok()) state.SkipWithError(r.message.c_str());
    sweeps = r.sweeps;
  }
  state.counters["sweeps"] = sweeps;
}
BENCHMARK(BM_BendSequencePlan)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The press brake along the part-only order, every bend with the standard
// tools. Argument as above.
void BM_PressBrakeCheck(benchmark::State& state) {
  Fixture& f = fixture();
  const BendSequenceResult order = plan_bend_sequence(f.part, f.spec);
  ToolSet tools = standard_tool_set(f.spec.thickness);
  tools.skip_clear_states = state.range(0) != 0;
  int made = 0;
  for (auto _ : state) {
    const PressBrakeResult r = check_press_brake(f.part, order.order, f.spec, tools);
    made = static_cast<int>(r.tooling.size());
  }
  state.counters["bends_made"] = made;
}
BENCHMARK(BM_PressBrakeCheck)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
