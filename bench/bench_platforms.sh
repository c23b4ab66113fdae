#!/usr/bin/env bash
# The platform figure of issue 15: in a folder written by
#   tsgraphs suite suites/platforms.yaml --out DIR
# pairs each building's final rooms at 0.3 m and at 1.7 m with those at 0.55 m
# (`tsgraphs eval --against`) and prints one row per pair, then the median and the worst of
# the paired f_re, DCS and d_center. Usage: bench/bench_platforms.sh DIR
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"
dir="${1:?usage: bench/bench_platforms.sh DIR}"
printf '| building | heights | N_a / N_b | N_re | f_re | DCS | d_center (m) |\n|---|---|---|---|---|---|---|\n'
for ref in "$dir"/cases/*-h055; do
  building="$(basename "$ref" -h055)"
  for other in h030 h170; do
    run="$dir/cases/$building-$other/ts-graphs"
    [ -d "$run" ] && [ -d "$ref/ts-graphs" ] || continue
    "$bin" -q eval "$run" --against "$ref/ts-graphs" > /dev/null
    python3 - "$run/comparison.json" "$building" "$other" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
f = lambda v: "-" if v is None else "%.2f" % v
print("| %s | %s / 0.55 m | %d / %d | %d | %s | %s | %s |" % (sys.argv[2], {"h030": "0.3", "h170": "1.7"}[sys.argv[3]] + " m",
      c["N_a"], c["N_b"], c["N_re"], f(c["f_re"]), f(c.get("dcs")), f(c.get("d_center"))))
PY
  done
done | tee /tmp/bench_platforms.$$ 
python3 - /tmp/bench_platforms.$$ <<'PY'
import sys, statistics
rows = [l.split("|")[1:-1] for l in open(sys.argv[1]) if l.startswith("| ")]
for name, col, worst in (("f_re", 4, min), ("DCS", 5, min), ("d_center", 6, max)):
    v = [float(r[col]) for r in rows if r[col].strip() != "-"]
    if v: print("%s: median %.2f, worst %.2f over %d pairs" % (name, statistics.median(v), worst(v), len(v)))
PY
rm -f /tmp/bench_platforms.$$
