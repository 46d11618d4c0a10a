// Clearance queries: our OpenVDB distance field against Embree's own
// closest-point query (rtcPointQuery) on the same >= 50 000-triangle mesh.
// Run through bench/run_environment_bench.sh, which writes the table in docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <random>

#include "../tests/native/env/test_meshes.hpp"
#include "sheetgen/env/distance_field.hpp"
#include "sheetgen/env/ray_caster.hpp"

namespace {

using namespace sheetgen;

// An icosphere of radius 0.5 m at level 6: 81 920 triangles; the sheet-metal voxel (1.6 mm).
struct Scene {
  TriangleMesh mesh = testing::icosphere(0.5, 6);
  DistanceFieldOptions options = [] {
    DistanceFieldOptions o;
    o.voxel_size = 1.6e-3;
    o.band_voxels = 5;  // what Environment picks for t = 1.6 mm and 1 mm clearance
    return o;
  }();
  std::unique_ptr<DistanceField> field;
  std::unique_ptr<RayCaster> rays;
  std::vector<Vec3> near_points, far_points, coherent_points;

  Scene() {
    field = std::make_unique<DistanceField>(mesh, options);
    rays = std::make_unique<RayCaster>(std::vector<const TriangleMesh*>{&mesh});
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (int i = 0; i < (1 << 16); ++i) {
      // Within the band, where clearance decisions are made.
      near_points.push_back(testing::random_surface_point(mesh, rng) + u01(rng) * 0.95 * field->band_width() * testing::random_unit(rng));
      // Anywhere in the sphere's bounding cube (mostly beyond the band).
      far_points.push_back(Vec3(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5) * 1.2);
    }
    // As the search asks them: runs of 64 samples over a 5 cm tab-sized patch
    // near the surface (polygon_contact subdivides a tab this way).
    while (coherent_points.size() < (1u << 16)) {
      const Vec3 c = testing::random_surface_point(mesh, rng);
      for (int k = 0; k < 64; ++k)
        coherent_points.push_back(c + 0.025 * Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1));
    }
  }
};

Scene& scene() {
  static Scene s;
  return s;
}

void BM_FieldDistance_NearSurface(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.field->distance(s.near_points[i++ & 0xFFFF]));
  state.SetItemsProcessed(state.iterations());
}

void BM_EmbreeClosestPoint_NearSurface(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.rays->closest_point(s.near_points[i++ & 0xFFFF]).distance);
  state.SetItemsProcessed(state.iterations());
}

void BM_FieldDistance_Anywhere(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.field->distance(s.far_points[i++ & 0xFFFF]));
  state.SetItemsProcessed(state.iterations());
}

void BM_EmbreeClosestPoint_Anywhere(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.rays->closest_point(s.far_points[i++ & 0xFFFF]).distance);
  state.SetItemsProcessed(state.iterations());
}

void BM_FieldClosestPoint_NearSurface(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.field->closest(s.near_points[i++ & 0xFFFF]).distance);
  state.SetItemsProcessed(state.iterations());
}

void BM_FieldDistance_Coherent(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.field->distance(s.coherent_points[i++ & 0xFFFF]));
  state.SetItemsProcessed(state.iterations());
}

void BM_EmbreeClosestPoint_Coherent(benchmark::State& state) {
  Scene& s = scene();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.rays->closest_point(s.coherent_points[i++ & 0xFFFF]).distance);
  state.SetItemsProcessed(state.iterations());
}

void BM_FieldBuild(benchmark::State& state) {
  Scene& s = scene();
  for (auto _ : state) {
    DistanceField f(s.mesh, s.options);
    benchmark::DoNotOptimize(f.stats().active_voxels);
    state.counters["memory_MiB"] = f.stats().memory_bytes / 1048576.0;
    state.counters["active_voxels"] = static_cast<double>(f.stats().active_voxels);
  }
  state.counters["triangles"] = static_cast<double>(s.mesh.triangles.size());
}

void BM_EmbreeBuild(benchmark::State& state) {
  Scene& s = scene();
  for (auto _ : state) {
    RayCaster r({&s.mesh});
    benchmark::DoNotOptimize(&r);
  }
}

BENCHMARK(BM_FieldDistance_NearSurface);
BENCHMARK(BM_EmbreeClosestPoint_NearSurface);
BENCHMARK(BM_FieldClosestPoint_NearSurface);
BENCHMARK(BM_FieldDistance_Anywhere);
BENCHMARK(BM_EmbreeClosestPoint_Anywhere);
BENCHMARK(BM_FieldDistance_Coherent);
BENCHMARK(BM_EmbreeClosestPoint_Coherent);
BENCHMARK(BM_FieldBuild)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_EmbreeBuild)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
