# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: their shared build, build-sanitize/ (or
# $SANITIZE_BUILD_DIR): clang, ASan + UBSan, libFuzzer coverage, RelWithDebInfo for stack traces
# with lines. Third-party libraries (PCL, rosbag, TBB, Embree) are not instrumented: their own
# memory is not checked, ours passed to them is.
sanitize_build="${SANITIZE_BUILD_DIR:-build-sanitize}"

configure_sanitize_build() {
  bash scripts/install-deps.sh --sanitize
  CC=clang CXX=clang++ cmake -S . -B "$sanitize_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTSGRAPHS_SANITIZE=ON -DTSGRAPHS_FUZZ=ON -DTSGRAPHS_BUILD_BENCH=OFF >/dev/null
}

# Leaks are checked at exit; any report aborts with its stack.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
