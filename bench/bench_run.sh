#!/usr/bin/env bash
# End-to-end benchmark of `tsgraphs run`: simulates a built-in scene once (cached under
# $TMPDIR), then times `run` on it and prints the real-time factor, T_PGO and the front-end
# figures from `eval`. Usage: bench/bench_run.sh [SCENE] [SEED]   (default: atrium 1)
# The user time beside the wall time: the host's speed per core moves between days by more
# than most changes, so compare binaries back to back, and CPU seconds as well as RTF.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"  # TSGRAPHS: another binary, to compare builds in one run
scene="${1:-atrium}"
seed="${2:-1}"
tmp="${TMPDIR:-/tmp}/tsgraphs-bench"
seq="$tmp/${scene}_seed${seed}"
mkdir -p "$tmp"
if [ ! -f "$seq/times.txt" ]; then
  "$bin" -q simulate "$scene" --seed "$seed" --out "$seq"
fi
# Warm the page cache so the figure measures the pipeline, not the disk.
cat "$seq"/scans/*.bin > /dev/null
/usr/bin/time -f "run: %e s wall, %U s user, %M KB peak" "$bin" -q run "$seq" --out "$tmp/${scene}_run" "${@:3}"
"$bin" -q eval "$tmp/${scene}_run" --seq "$seq"
python3 -c "import json,sys; d=json.load(open('$tmp/${scene}_run/run_info.json')); print('rtf %.1f, sequence %.1f s, wall %.2f s, T_PGO %.3f s over %d optimisations' % (d['rtf'], d['sequence_duration_s'], d['wall_time_s'], d['t_pgo_s'], d['num_optimizations']))"
