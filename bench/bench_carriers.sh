#!/usr/bin/env bash
# Issue 16's platform figures from a folder written by
#   tsgraphs suite suites/carriers.yaml --out DIR
# One row per case: the measured sensor height against the scene's mount height, the ground's
# precision and recall (0.5-15 m), rooms F1, and F1's difference from the same building walked
# by the wheeled platform; then per platform the median and the worst of each.
# Usage: bench/bench_carriers.sh DIR
set -euo pipefail
dir="${1:?usage: bench/bench_carriers.sh DIR}"
python3 - "$dir" <<'PY'
import json, os, re, statistics, sys
root = os.path.join(sys.argv[1], "cases")
rows = {}
for case in sorted(os.listdir(root)):
    m = re.match(r"(.+)-(wheeled|hand10|hand2|legged)$", case)
    run = os.path.join(root, case, "ts-graphs")
    if not m or not os.path.isfile(os.path.join(run, "metrics.json")):
        continue
    scene = open(os.path.join(root, case, "scene.yaml")).read()
    mount = float(re.search(r"mount_height: ([0-9.]+)", scene).group(1))
    info = json.load(open(os.path.join(run, "run_info.json")))
    metrics = json.load(open(os.path.join(run, "metrics.json")))
    rows[(m.group(1), m.group(2))] = dict(
        mount=mount, height=info["platform"]["sensor_height"], P=metrics["ground"]["precision"],
        R=metrics["ground"]["recall"], F1=metrics["rooms_gt"]["f1"])
print("| case | platform | mount (m) | measured (m) | error (m) | ground P | ground R | rooms F1 | F1 - wheeled |")
print("|---|---|---|---|---|---|---|---|---|")
f = lambda v: "-" if v is None else "%.3f" % v
per = {}
for (building, platform), r in sorted(rows.items()):
    wheeled = rows.get((building, "wheeled"))
    d = None if wheeled is None or r["F1"] is None or wheeled["F1"] is None else r["F1"] - wheeled["F1"]
    err = r["height"] - r["mount"]
    print("| %s | %s | %.2f | %.3f | %+.3f | %s | %s | %s | %s |" % (building, platform, r["mount"], r["height"], err,
          f(r["P"]), f(r["R"]), f(r["F1"]), f(d)))
    p = per.setdefault(platform, {"|error|": [], "ground P": [], "ground R": [], "rooms F1": [], "F1 - wheeled": []})
    p["|error|"].append(abs(err))
    for key, v in (("ground P", r["P"]), ("ground R", r["R"]), ("rooms F1", r["F1"]), ("F1 - wheeled", d)):
        if v is not None:
            p[key].append(v)
print()
for platform in ("wheeled", "hand10", "hand2", "legged"):
    if platform not in per:
        continue
    parts = []
    for key, v in per[platform].items():
        if not v:
            continue
        worst = max(v) if key == "|error|" else min(v)
        parts.append("%s median %.3f, worst %.3f" % (key, statistics.median(v), worst))
    print("%s (%d cases): %s" % (platform, len(per[platform]["|error|"]), "; ".join(parts)))
PY
