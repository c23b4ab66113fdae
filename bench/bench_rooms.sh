#!/usr/bin/env bash
# The room layer side by side: TS-graphs (traversable + flush), S-Graphs+ (esdf + timer) and the
# two ablations, on built-in scenes (simulated once, cached under $TMPDIR). Prints one row per
# scene and mode: Table 1's figures, the ground-truth room figures, the room layer's front-end
# time per keyframe and T_PGO. Usage: [TSGRAPHS=binary] bench/bench_rooms.sh [SEED] [SCENE...]  (default: 1 atrium office)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"  # TSGRAPHS=another binary compares two builds
seed="${1:-1}"
shift || true
if [ $# -gt 0 ]; then scenes=("$@"); else scenes=(atrium office); fi
tmp="${TMPDIR:-/tmp}/tsgraphs-bench"
mkdir -p "$tmp"
printf '| scene | mode | N1st | N2nd | N_re | f_re | DCS | d_center (m) | ATE_rmse (m) | T_PGO (s) | P / R / F1 | under / over | rooms ms per keyframe (mean / p95) |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for scene in "${scenes[@]}"; do
  seq="$tmp/${scene}_seed${seed}"
  [ -f "$seq/times.txt" ] || "$bin" -q simulate "$scene" --seed "$seed" --out "$seq"
  for mode in "traversable flush TS-graphs" "esdf timer S-Graphs+" "traversable timer ablation" "esdf flush ablation"; do
    set -- $mode
    run="$tmp/${scene}_rooms_$1_$2"
    "$bin" -q run "$seq" --out "$run" --free-space "$1" --room-trigger "$2"
    "$bin" -q eval "$run" --seq "$seq" > /dev/null
    python3 - "$run" "$scene" "$3 ($1 + $2)" <<'PY'
import csv, json, sys
run, scene, mode = sys.argv[1:]
m = json.load(open(run + "/metrics.json"))
c, g, t, p = m["consistency"], m["rooms_gt"], m["trajectory"], m["pgo"]
rows = [r for r in csv.DictReader(open(run + "/timings.csv")) if r.get("kind", "scan") == "scan" and int(r["keyframe"]) >= 0]
ms = sorted(float(r["rooms_ms"]) for r in rows)
f = lambda v, fmt="%.2f": "-" if v is None else fmt % v
print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s / %s | %s / %s | %.1f / %.1f |" % (
    scene, mode, f(c["N1st"], "%.0f"), f(c["N2nd"], "%.0f"), f(c["N_re"], "%.0f"), f(c["f_re"]), f(c["dcs"]),
    f(c["d_center"]), f(t["ate_rmse"], "%.3f"), f(p["t_pgo_s"], "%.3f"), f(g["precision"]), f(g["recall"]), f(g["f1"]),
    f(g["under_segmented"], "%.0f"), f(g["over_segmented"], "%.0f"),
    sum(ms) / len(ms), ms[int(0.95 * (len(ms) - 1))]))
PY
  done
done
