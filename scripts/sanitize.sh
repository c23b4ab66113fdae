#!/usr/bin/env bash
# The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer, and run under
# them: any memory error, leak or undefined behaviour fails the test it happens in.
# Usage: bash scripts/sanitize.sh [ctest arguments, e.g. -R PipelineConfig]
# Builds in build-sanitize/ (RelWithDebInfo, for stack traces with lines); about three times
# the Release build's time, and the suite runs two to three times slower.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${SANITIZE_BUILD_DIR:-build-sanitize}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTSGRAPHS_SANITIZE=ON -DTSGRAPHS_BUILD_BENCH=OFF
cmake --build "$build"
# Leaks are checked at exit; a report aborts with the stack. Third-party libraries (TBB,
# Embree, PCL) are not instrumented: their own memory is not checked, ours passed to them is.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$build" --output-on-failure "$@"
