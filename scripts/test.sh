#!/usr/bin/env bash
# The test suite on a fresh Debian bookworm machine: installs what the project
# needs, builds, and runs the tests. Exit status 0 = all passed.
#
#   bash scripts/test.sh          # fast tier (what .ci/run runs; <= 20 min from a cold ccache)
#   bash scripts/test.sh --full   # fast tier + the slow checks (about two hours; docs/testing.md)
#
# Fast tier: every GoogleTest unit and property test except the CalculiX
# comparisons, the Python checks, the tests inside `blender -b`, every sample
# scene solved at reduced settings and checked by verify without CalculiX, the
# areas core, part and fem again under ASan + UBSan, and the saved fuzz
# inputs replayed. The full tier adds every test labelled `full` (CalculiX and
# solid-model checks of the sample parts, the scenes at the default settings,
# the heavy convergence studies), the search areas and the CLI under the
# sanitizers, and bounded fuzzing (FUZZ_SECONDS per target, default 60).
# docs/testing.md says which test is where and why.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
FULL=0
for arg in "$@"; do
  case "$arg" in
    --full) FULL=1 ;;
    *) echo "test.sh: unknown argument '$arg' (only --full is known)" >&2; exit 1 ;;
  esac
done

LOGS="$BUILD_DIR/test-logs"
start=$SECONDS
stage() { echo "== $1 (at $((SECONDS - start)) s)"; }

bash "$ROOT/scripts/install_deps.sh"
stage "build ($BUILD_DIR)"
# The benchmarks are built by the full tier only: no fast test runs them.
if [ "$FULL" = 1 ]; then BENCH=ON; else BENCH=OFF; fi
BUILD_DIR="$BUILD_DIR" bash "$ROOT/scripts/build.sh" -DSHEETGEN_BENCH="$BENCH"
mkdir -p "$LOGS"
rm -f "$LOGS"/*.log

# Each ctest run's log is kept so the closing line can add up every run.
status=0
run_ctest() {  # run_ctest NAME CTEST-ARGS...
  local name="$1"; shift
  set +e
  ctest "$@" --output-on-failure </dev/null 2>&1 | tee "$LOGS/$name.log"
  local rc=${PIPESTATUS[0]}
  set -e
  if [ "$rc" -ne 0 ]; then status=1; fi
}

stage "tests"
if [ "$FULL" = 1 ]; then
  run_ctest tests --test-dir "$BUILD_DIR" -j "$(nproc)"
else
  run_ctest tests --test-dir "$BUILD_DIR" -j "$(nproc)" -LE full
fi

stage "sanitizers (ASan + UBSan, build-sanitize/)"
set +e
if [ "$FULL" = 1 ]; then
  # Every area and the CLI under ASan, except the `full` checks and the ten
  # scenes of solve_samples_fast: they run the pipeline the other CLI tests
  # (hard cases, determinism, decks, farm) already run under ASan, on more
  # scenes and at larger settings, and would take hours at ASan's speed
  # (solve_samples_fast passed 1500 s unfinished; the CalculiX checks take
  # 400-1900 s each in Release). Their value is the comparison with CalculiX
  # and the solid model, which the Release run above makes.
  bash "$ROOT/scripts/sanitize.sh" -LE full -E '^solve_samples_fast$' </dev/null 2>&1 | tee "$LOGS/sanitize.log"
else
  # The search areas (discovery, structure, compose) take over 20 minutes under
  # ASan; the fast tier runs three areas below them, which every search builds
  # on: core (the readers), part and fem. env's tests are the full tier's: its
  # exact-contact tests alone take 3 minutes under ASan, and its code is mostly
  # the doors to OpenVDB and Embree. The CLI those tests drive is the Release
  # one (it needs every search area).
  # The OpenVDB door is uninstrumented here, the Release build's object
  # (native/sheetgen/env/CMakeLists.txt says why).
  SANITIZE_TARGETS="sheetgen_core_tests sheetgen_part_tests sheetgen_fem_tests" SANITIZE_OPENVDB=OFF \
  SANITIZE_DISTANCE_FIELD_OBJECT="$BUILD_DIR/native/sheetgen/env/CMakeFiles/sheetgen_env.dir/distance_field.cpp.o" \
  SHEETGEN_CLI="$BUILD_DIR/native/cli/sheetgen" \
    bash "$ROOT/scripts/sanitize.sh" -L "core|part|fem" -LE full </dev/null 2>&1 | tee "$LOGS/sanitize.log"
fi
if [ "${PIPESTATUS[0]}" -ne 0 ]; then status=1; fi
set -e

set +e
if [ "$FULL" = 1 ]; then
  stage "fuzzers (${FUZZ_SECONDS:-60} s per target, build-fuzz/)"
  FUZZ_SECONDS="${FUZZ_SECONDS:-60}" bash "$ROOT/scripts/fuzz.sh" </dev/null 2>&1 | tee "$LOGS/fuzz.log"
else
  stage "fuzz inputs replayed (build-fuzz/)"
  bash "$ROOT/scripts/fuzz.sh" --replay </dev/null 2>&1 | tee "$LOGS/fuzz.log"
fi
if [ "${PIPESTATUS[0]}" -ne 0 ]; then status=1; fi
set -e

# One closing line over every ctest run (ctest prints one per run).
passed=0; failed=0
for log in "$LOGS"/*.log; do
  line=$(grep -E "tests passed, [0-9]+ tests? failed out of [0-9]+" "$log" | tail -1 || true)
  if [ -n "$line" ]; then
    f=$(echo "$line" | sed -E 's/.* ([0-9]+) tests? failed out of ([0-9]+).*/\1/')
    n=$(echo "$line" | sed -E 's/.* failed out of ([0-9]+).*/\1/')
    passed=$((passed + n - f)); failed=$((failed + f))
  elif [ "$(basename "$log")" != fuzz.log ]; then
    failed=$((failed + 1))   # a stage that never reached ctest (a build failure) counts as a failure
  fi
done
tier=fast; if [ "$FULL" = 1 ]; then tier=full; fi
echo "test.sh ($tier tier, $((SECONDS - start)) s)"
echo "tests: $passed passed, $failed failed"
if [ "$failed" -ne 0 ]; then status=1; fi
exit "$status"
