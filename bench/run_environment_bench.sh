#!/usr/bin/env bash
# Runs the environment benchmark once and prints the docs/benchmarks.md table:
# our distance field against Embree's rtcPointQuery on the same 81 920-triangle
# mesh, as ratios measured in the same run, plus build time and memory.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
out="$(mktemp)"
"$BUILD_DIR/bench/environment_bench" --benchmark_format=json --benchmark_repetitions="${REPS:-3}" \
  --benchmark_report_aggregates_only=true > "$out"
/usr/bin/python3 - "$out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
ctx = d["context"]
rows = {b["run_name"]: b for b in d["benchmarks"] if b.get("aggregate_name") == "median"}
def ips(name): return rows[name]["items_per_second"]
print("Machine: %d CPUs at %s MHz, %s; load average %s" % (ctx["num_cpus"], ctx["mhz_per_cpu"], ctx.get("host_name", ""),
      ", ".join("%.2f" % x for x in ctx.get("load_avg", []))))
print()
print("| query set | distance field (queries/s) | Embree rtcPointQuery (queries/s) | ratio field/Embree |")
print("| --- | ---: | ---: | ---: |")
for label, f, e in [("random points in the narrow band", "BM_FieldDistance_NearSurface", "BM_EmbreeClosestPoint_NearSurface"),
                    ("coherent runs (64 points per 5 cm patch)", "BM_FieldDistance_Coherent", "BM_EmbreeClosestPoint_Coherent"),
                    ("random points in the bounding cube", "BM_FieldDistance_Anywhere", "BM_EmbreeClosestPoint_Anywhere")]:
    print("| %s | %.3g | %.3g | %.2f |" % (label, ips(f), ips(e), ips(f) / ips(e)))
print("| closest point + gradient (field), random in band | %.3g | | |" % ips("BM_FieldClosestPoint_NearSurface"))
b = rows["BM_FieldBuild/iterations:2"]
e = rows["BM_EmbreeBuild/iterations:2"]
print()
print("Build: distance field %.2f s (%d active voxels, %.0f MiB for distance + index grids, %d triangles); Embree BVH %.3f s."
      % (b["real_time"] / 1e3, b["active_voxels"], b["memory_MiB"], b["triangles"], e["real_time"] / 1e3))
PY
rm -f "$out"
