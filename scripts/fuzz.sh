#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang, ASan + UBSan) in their own
# build dir (default build-fuzz/) and runs each for a bounded time on its seed
# corpus. Exit status non-zero when a target crashes, hangs, leaks or blows up
# memory; the input that did it is saved in $FUZZ_ARTIFACTS/<target>/ (and the
# libFuzzer log next to it) to become a regression test.
#
#   bash scripts/fuzz.sh                          # every target, 60 s each
#   FUZZ_SECONDS=600 bash scripts/fuzz.sh fuzz_mesh_readers
#   bash scripts/fuzz.sh --replay                 # only replay the saved inputs (the fast test tier)
#
# Every run first replays the saved regressions and the seed corpus through
# ctest (tests/fuzz/CMakeLists.txt); --replay stops there.
#
# Environment: FUZZ_SECONDS (per target, default 60), FUZZ_BUILD_DIR,
# FUZZ_ARTIFACTS (default $FUZZ_BUILD_DIR/artifacts), FUZZ_JOBS (parallel
# fuzzing processes per target, default 1: the machine is shared),
# FUZZ_RSS_MB (default 2048), FUZZ_MALLOC_MB (largest single allocation, default 512).
# New corpus entries go to $FUZZ_BUILD_DIR/corpus/<target>/, never into the
# source tree (copy interesting ones into tests/fuzz/corpus/ by hand).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
ARTIFACTS="${FUZZ_ARTIFACTS:-$BUILD_DIR/artifacts}"
SECONDS_PER_TARGET="${FUZZ_SECONDS:-60}"
JOBS="${FUZZ_JOBS:-1}"
RSS_MB="${FUZZ_RSS_MB:-2048}"
MALLOC_MB="${FUZZ_MALLOC_MB:-512}"
# shellcheck source=scripts/ccache_env.sh
source "$ROOT/scripts/ccache_env.sh"

ALL_TARGETS=(fuzz_problem_json fuzz_mesh_readers)
REPLAY_ONLY=0
if [ "${1:-}" = "--replay" ]; then REPLAY_ONLY=1; shift; fi
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=("${ALL_TARGETS[@]}"); fi

bash "$ROOT/scripts/install_deps.sh"
echo "== build fuzzers ($BUILD_DIR, clang, libFuzzer + ASan + UBSan)"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$ROOT/tests/fuzz" -B "$BUILD_DIR" -G Ninja -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" >/dev/null
cmake --build "$BUILD_DIR" -j 2 --target "${TARGETS[@]}"

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

echo "== replay of the saved inputs"
replay_regex="^($(IFS='|'; echo "${TARGETS[*]}"))_replay\$"
ctest --test-dir "$BUILD_DIR" -L fuzz -R "$replay_regex" --output-on-failure </dev/null
if [ "$REPLAY_ONLY" = 1 ]; then exit 0; fi

failed=()
for t in "${TARGETS[@]}"; do
  seeds="$ROOT/tests/fuzz/corpus/$t"
  regressions="$ROOT/tests/fuzz/regressions/$t"
  work="$BUILD_DIR/corpus/$t"
  out="$ARTIFACTS/$t"
  mkdir -p "$work" "$out"
  log="$out/fuzz.log"
  echo "== $t: ${SECONDS_PER_TARGET} s (rss limit ${RSS_MB} MB, malloc limit ${MALLOC_MB} MB)"
  # First the regression inputs (must all pass), then fuzz from the seeds.
  if compgen -G "$regressions/*" >/dev/null; then
    if ! "$BUILD_DIR/$t" -rss_limit_mb="$RSS_MB" -malloc_limit_mb="$MALLOC_MB" -timeout=10 "$regressions"/* >"$out/regressions.log" 2>&1; then
      echo "$t: a regression input fails again (see $out/regressions.log)" >&2
      failed+=("$t")
      continue
    fi
  fi
  parallel=()
  if [ "$JOBS" -gt 1 ]; then parallel=(-jobs="$JOBS" -workers="$JOBS"); fi
  set +e
  "$BUILD_DIR/$t" "$work" "$seeds" \
    -dict="$ROOT/tests/fuzz/dict/$t.dict" \
    -max_total_time="$SECONDS_PER_TARGET" -timeout=10 \
    -rss_limit_mb="$RSS_MB" -malloc_limit_mb="$MALLOC_MB" -max_len=16384 \
    "${parallel[@]}" \
    -artifact_prefix="$out/" -print_final_stats=1 >"$log" 2>&1
  rc=$?
  set -e
  # With -jobs > 1 libFuzzer writes fuzz-N.log files in the current directory.
  for f in fuzz-[0-9]*.log; do if [ -e "$f" ]; then cat "$f" >>"$log"; rm -f "$f"; fi; done
  # Statistics only: never let a missing line stop the script (set -e, pipefail).
  execs=$(grep -a -E "^stat::number_of_executed_units" "$log" | awk '{s += $2} END {print s + 0}' || true)
  cov=$(grep -a -E "^#[0-9]+.*(DONE|pulse|NEW|REDUCE).*cov:" "$log" | tail -1 | sed -E 's/.*cov: ([0-9]+).*ft: ([0-9]+).*/cov \1 ft \2/' || true)
  echo "$t: exit $rc, $execs executions, $cov (log $log)"
  if [ $rc -ne 0 ]; then
    echo "$t: CRASH - inputs saved in $out:" >&2
    ls "$out" | grep -E "^(crash|leak|timeout|oom|slow-unit)-" >&2 || true
    grep -a -E "ERROR|runtime error|contract broken|deadly signal" "$log" | head -5 >&2 || true
    failed+=("$t")
  fi
done

if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: failing targets: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: all targets clean"
