#!/usr/bin/env bash
# Each reader's fuzz target (tests/fuzz/) under libFuzzer with ASan + UBSan, for a bounded time,
# starting from its seed corpus. An input that crashes, leaks, takes longer than 10 s or more
# than 2 GB is saved as fuzz-out/<target>/{crash,leak,timeout,oom}-<hash>; rerun one with
# `build-sanitize/tests/fuzz/fuzz_<target> FILE`. Exit 1 when any target found something.
# Usage: bash scripts/fuzz.sh [SECONDS_PER_TARGET=600] [TARGET...]   (FUZZ_JOBS=2 at a time)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/sanitize_build.sh
seconds="${1:-600}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(pcd kitti tum point_cloud2 ros_bag run_folder occupancy_map scene params)
fi
configure_sanitize_build
cmake --build "$sanitize_build" --target "${targets[@]/#/fuzz_}"

out=fuzz-out
fuzz_one() {
  local t="$1" dir="$out/$1"
  mkdir -p "$dir/corpus"
  # What an earlier run found is not this run's finding (the corpus it grew is kept).
  find "$dir" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) -delete
  # -use_value_profile: compares of length words against the bytes left guide the search.
  "$sanitize_build/tests/fuzz/fuzz_$t" "$dir/corpus" "tests/fuzz/corpus/$t" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -use_value_profile=1 -print_final_stats=1 \
    -artifact_prefix="$dir/" >"$dir/log.txt" 2>&1 || true
}
export -f fuzz_one
export out seconds sanitize_build
printf '%s\n' "${targets[@]}" | xargs -P "${FUZZ_JOBS:-2}" -I{} bash -c 'fuzz_one {}'

status=0
printf '%-15s %12s %8s %10s %s\n' target inputs cov corpus found
for t in "${targets[@]}"; do
  log="$out/$t/log.txt"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  corpus=$(find "$out/$t/corpus" -type f | wc -l)
  found=$(find "$out/$t" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  printf '%-15s %12s %8s %10s %s\n' "$t" "${runs:-?}" "${cov:-?}" "$corpus" "$found"
  if [ "$found" -ne 0 ] || [ -z "$runs" ]; then status=1; fi
done
exit $status
