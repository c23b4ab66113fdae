#!/usr/bin/env bash
# Long runs (issue 17): does the back-end's cost follow the building or the length of the run?
# Simulates SCENE walked LAPS laps (cached under $TMPDIR/tsgraphs-bench/laps), runs
# `tsgraphs run` on it (given odometry) under /usr/bin/time, evaluates it against the
# simulator's ground truth, and prints from timings.csv:
#   - the mean and p95 solve time of the first and the last tenth of the run (by stamp),
#   - the keyframes in the graph at the end of lap 1 and at the end, and their growth,
#   - T_PGO, the real-time factor and peak RSS; ATE_rmse and the room figures from eval.
# Usage: bench/bench_laps.sh SCENE LAPS RUN_DIR [run options...]
#   SCENE: a built-in scene name or a scene file (a generated building: `tsgraphs generate`).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"
if [ $# -lt 3 ]; then
  echo "usage: bench/bench_laps.sh SCENE LAPS RUN_DIR [run options...]" >&2
  exit 2
fi
scene="$1"
laps="$2"
run="$3"
shift 3
tmp="${TMPDIR:-/tmp}/tsgraphs-bench/laps"
seq="$tmp/$(basename "${scene%.yaml}")_laps${laps}"
mkdir -p "$tmp"
if [ ! -f "$seq/times.txt" ]; then
  "$bin" -q simulate "$scene" --seed 1 --laps "$laps" --out "$seq"
fi
rm -rf "$run"
/usr/bin/time -f "%e %M" -o "$run.time" "$bin" -q run "$seq" --out "$run" "$@"
"$bin" -q eval "$run" --seq "$seq" > /dev/null
/usr/bin/python3 - "$run" "$seq" "$laps" "$run.time" <<'EOF'
import csv, json, math, sys
run, seq, laps, timefile = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
wall, rss_kb = open(timefile).read().split()[-2:]
rows = list(csv.DictReader(open(run + "/timings.csv")))
opt = [r for r in rows if r["kind"] == "optimization"]
scans = [r for r in rows if r["kind"] == "scan"]
t0, t1 = float(scans[0]["stamp"]), float(scans[-1]["stamp"])
span = t1 - t0
def stats(sel):
    s = sorted(float(r["optimization_s"]) * 1e3 for r in sel)
    if not s:
        return float("nan"), float("nan"), 0
    return sum(s) / len(s), s[min(len(s) - 1, int(math.ceil(0.95 * len(s))) - 1)], len(s)
first = [r for r in opt if float(r["stamp"]) <= t0 + span / 10]
last = [r for r in opt if float(r["stamp"]) >= t1 - span / 10]
def active_at(t):
    # Keyframes in the graph at stamp t: the column active_keyframes where written, else every
    # keyframe made so far.
    if "active_keyframes" in opt[0]:
        before = [r for r in opt if float(r["stamp"]) <= t]
        return int(before[-1]["active_keyframes"]) if before else 0
    return sum(1 for r in scans if int(r["keyframe"]) >= 0 and float(r["stamp"]) <= t)
lap1 = active_at(t0 + span / laps)
end = active_at(t1 + 1)
made = sum(1 for r in scans if int(r["keyframe"]) >= 0)
m = json.load(open(run + "/metrics.json"))
info = json.load(open(run + "/run_info.json"))
fm, fp, fn = stats(first)
lm, lp, ln = stats(last)
print(f"run {run}: {len(scans)} scans, {laps} laps, wall {float(wall):.1f} s, RTF {info['rtf']:.1f}, peak RSS {int(rss_kb) / 1024:.0f} MB")
print(f"solve ms, first tenth: mean {fm:.1f} p95 {fp:.1f} ({fn} solves); last tenth: mean {lm:.1f} p95 {lp:.1f} ({ln}); last/first mean {lm / fm:.2f}")
print(f"keyframes in the graph: {lap1} after lap 1, {end} at the end (growth {100.0 * (end - lap1) / lap1:.1f} %); {made} made")
print(f"T_PGO {info['t_pgo_s']:.2f} s over {info['num_optimizations']} optimisations")
def get(*path):
    d = m
    for p in path:
        d = d.get(p) if isinstance(d, dict) else None
    return "-" if d is None else (f"{d:.3f}" if isinstance(d, float) else str(d))
print(f"ATE_rmse {get('trajectory', 'ate_rmse')} m (odometry {get('trajectory', 'odom_ate_rmse')}), ATE_loop {get('trajectory', 'ate_loop')} m; "
      f"loops {get('loops', 'n_loops_correct')} correct of {get('loops', 'n_loops')} (room-proposed {get('loops', 'n_loops_room_correct')} of {get('loops', 'n_loops_room')})")
print(f"rooms vs truth: P {get('rooms_gt', 'precision')} R {get('rooms_gt', 'recall')} F1 {get('rooms_gt', 'f1')} "
      f"(under {get('rooms_gt', 'under_segmented')}, over {get('rooms_gt', 'over_segmented')}, {get('rooms_gt', 'n_rooms_final')} final); "
      f"f_re {get('consistency', 'f_re')} DCS {get('consistency', 'dcs')} d_center {get('consistency', 'd_center')}")
EOF
