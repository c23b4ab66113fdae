#!/usr/bin/env bash
# LiDAR odometry on the carriers' buildings (issue 16's drift goal): for each case folder of a
# carriers suite run (`tsgraphs suite suites/carriers.yaml --out DIR`, or one case of it with
# --case NAME: only its scene.yaml is used) whose name matches PATTERN, simulates the case's
# sequence into SEQ_DIR (once: kept for later runs) and runs bench_odometry on it, with any
# further options (e.g. --fine-threshold 0 --recovery-search 0 for the odometry before issue 16's
# fifth sitting). One row per case, then the median and the worst ATE and drifts per platform.
#   bench/bench_odometry_carriers.sh DIR SEQ_DIR [PATTERN] [bench_odometry options...]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"
bench="${BENCH_ODOMETRY:-$here/build/bench/bench_odometry}"
dir="${1:?usage: bench/bench_odometry_carriers.sh DIR SEQ_DIR [PATTERN] [options...]}"
seqs="${2:?usage: bench/bench_odometry_carriers.sh DIR SEQ_DIR [PATTERN] [options...]}"
pattern="${3:-*}"
shift $(( $# < 3 ? $# : 3 ))
mkdir -p "$seqs"
rows="$(mktemp)"
trap 'rm -f "$rows"' EXIT
printf '| case | scans | path (m) | ATE_rmse (m) | max drift | final error | lost scans | ms / scan | segment drift |\n|---|---|---|---|---|---|---|---|---|\n'
for scene in "$dir"/cases/$pattern/scene.yaml; do
  [ -f "$scene" ] || continue
  case_name="$(basename "$(dirname "$scene")")"
  seq="$seqs/$case_name"
  [ -f "$seq/times.txt" ] || "$bin" -q simulate "$scene" --out "$seq"
  "$bench" "$seq" --threads 1 "$@" | awk -v c="$case_name" '
    /^scans/ {n = $2} /^path length/ {p = $3} /^ATE rmse/ {a = $3} /^max drift/ {d = $3}
    /^final error/ {f = $3} /^lost scans/ {l = $3} /^wall time/ {m = substr($5, 2)} /^segment drift/ {g = $3}
    END {printf "| %s | %s | %.0f | %s | %s %% | %s m | %s | %s | %s %% |\n", c, n, p, a, d, f, l, m, g}'
done | tee "$rows"
python3 - "$rows" <<'PY'
import math, statistics, sys
groups = {}
for line in open(sys.argv[1]):
    cells = [c.strip() for c in line.split("|")[1:-1]]
    value = lambda s: math.inf if "nan" in s or "inf" in s else float(s.split()[0])
    platform = cells[0].rsplit("-", 1)[-1]
    groups.setdefault(platform, []).append((value(cells[3]), value(cells[4]), value(cells[8])))
for platform, v in sorted(groups.items()):
    ate = [a for a, _, _ in v]
    drift = [d for _, d, _ in v]
    segment = [g for _, _, g in v]
    print("%s: %d cases, ATE_rmse median %.3f m, worst %.3f m; max drift median %.2f %%, worst %.2f %%; "
          "segment drift median %.2f %%, worst %.2f %%, <= 1 %% in %d"
          % (platform, len(v), statistics.median(ate), max(ate), statistics.median(drift), max(drift),
             statistics.median(segment), max(segment), sum(g <= 1.0 for g in segment)))
PY
