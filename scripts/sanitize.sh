#!/usr/bin/env bash
# The GoogleTest suite under AddressSanitizer + UndefinedBehaviorSanitizer, in
# its own build dir (default build-sanitize/): configures with
# -DSHEETGEN_SANITIZE=ON (no Python module, no benchmarks), builds the CLI and
# the test executables, and runs ctest there. Any ASan/UBSan/LSan report fails
# the run (UBSan is built with -fno-sanitize-recover, ASan aborts by default).
#
#   bash scripts/sanitize.sh                  # everything
#   bash scripts/sanitize.sh -L core          # extra arguments go to ctest
#
# Environment: SANITIZE_BUILD_DIR, SANITIZE_TARGETS, SANITIZE_OPENVDB (OFF: leave the
# OpenVDB door uninstrumented; default ON), SANITIZE_DISTANCE_FIELD_OBJECT (with
# SANITIZE_OPENVDB=OFF: link this uninstrumented distance_field.cpp.o of another
# build instead of compiling it), JOBS (compile jobs; default 2).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${SANITIZE_BUILD_DIR:-$ROOT/build-sanitize}"
JOBS="${JOBS:-2}"
# shellcheck source=scripts/ccache_env.sh
source "$ROOT/scripts/ccache_env.sh"

bash "$ROOT/scripts/install_deps.sh"
echo "== configure + build ($BUILD_DIR, ASan + UBSan)"
# -O1 -g1: the optimisation ASan's documentation recommends, and line tables
# for readable reports. Full -O2 -g compiled the OpenVDB translation unit
# alone in 260 s under ASan from a cold cache (the fast tier's budget is 20 min).
# clang (SANITIZE_CC / SANITIZE_CXX to change it): the fast tier's instrumented
# core, part and fem areas compile and run in 243 s with clang 14 against
# 356 s with gcc 12 (ccache off; a test batch in half gcc's time, the FEM's
# library files in a third to a half less); the Release build stays on gcc.
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_C_COMPILER="${SANITIZE_CC:-clang}" -DCMAKE_CXX_COMPILER="${SANITIZE_CXX:-clang++}" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS="-O1 -g1 -DNDEBUG" \
  -DSHEETGEN_SANITIZE=ON -DSHEETGEN_SANITIZE_OPENVDB="${SANITIZE_OPENVDB:-ON}" \
  -DSHEETGEN_DISTANCE_FIELD_OBJECT="${SANITIZE_DISTANCE_FIELD_OBJECT:-}" \
  -DSHEETGEN_PYTHON=OFF -DSHEETGEN_BENCH=OFF -DSHEETGEN_TESTS=ON >/dev/null
# SANITIZE_TARGETS (optional): build only these targets (the test command builds
# the fast areas' tests; everything by default).
if [ -n "${SANITIZE_TARGETS:-}" ]; then
  # shellcheck disable=SC2086
  cmake --build "$BUILD_DIR" -j "$JOBS" --target $SANITIZE_TARGETS
else
  cmake --build "$BUILD_DIR" -j "$JOBS"
fi

# Third-party leaks we cannot fix, one `leak:<symbol or module>` per line.
# OpenCASCADE's STEP writer keeps objects in static registries (its
# IFSelect_Editor instances and GeomToStep's cached directions among them) that
# are never freed: LeakSanitizer reports them at exit of every test that writes
# a STEP file. Debian's OCCT has no frame pointers, so the reports stop at the
# OCCT frame that allocated (Standard_MMgrRaw::Allocate) and can only be matched
# by module. Fontconfig, which cairo's text calls load, keeps its
# configuration and font patterns in a process-wide cache that is freed only by
# FcFini, which a library must not call (another user of fontconfig in the
# process would lose its cache): every test that draws text (the convergence
# plot, the drawing sheet, and the CLI that writes them) leaks it at exit,
# from frames inside libfontconfig.
SUPP="$BUILD_DIR/lsan.supp"
printf '%s\n' "leak:libTKernel.so" "leak:libTKXSBase.so" "leak:libTKSTEP.so" "leak:libfontconfig.so" >"$SUPP"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:abort_on_error=0:halt_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$SUPP}"

echo "== tests under ASan + UBSan"
# Sanitized code is 2-5x slower: a generous per-test timeout. -j 2 for the shared machine.
set +e
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS" --timeout 1800 "$@" </dev/null 2>&1 | tee "$BUILD_DIR/ctest.log"
status=${PIPESTATUS[0]}
set -e
# A sanitizer report inside a test that still exited 0 (e.g. from a child
# process whose exit code a test ignored) must fail the run too.
if grep -E -q "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" "$BUILD_DIR/ctest.log"; then
  echo "sanitize: sanitizer reports found in the test output (see $BUILD_DIR/ctest.log)" >&2
  status=1
fi
exit "$status"
