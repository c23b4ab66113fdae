#!/usr/bin/env bash
# segment-map on the real floor plans of ../shared/data/floorplans, whole map, beside ROSE2's
# published figures for the same maps (that folder's README: goldleaf3i/declutter-reconstruct,
# "evaluation4 geometric.txt"): IPA micro precision and recall, room F1 at IoU 0.5, segments,
# time. Usage: [TSGRAPHS=binary] bench/bench_segment_map.sh [CONFIG.yaml] [FLOORPLANS_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"  # TSGRAPHS=another binary compares two builds
config="${1:-}"
plans="${2:-$here/../shared/data/floorplans}"
out="${TMPDIR:-/tmp}/tsgraphs-segment-map"
mkdir -p "$out"
maps=(g4s_y2 map17 map23 map_with_clutter photo_2020 ubremen-cartesium-demo4)
for m in "${maps[@]}"; do
  "$bin" -q segment-map "$plans/$m.yaml" --rooms "$plans/${m}_rooms.png" --out "$out/$m.png" --metrics "$out/$m.json" \
    ${config:+--config "$config"} > /dev/null
done
python3 - "$out" "${maps[@]}" <<'PY'
import json, statistics, sys
out, maps = sys.argv[1], sys.argv[2:]
# ROSE2's micro precision and recall, % (../shared/data/floorplans/README.md).
rose = {"g4s_y2": (91.7, 94.3), "map17": (79.8, 91.3), "map23": (88.8, 97.7), "map_with_clutter": (67.9, 85.3),
        "photo_2020": (91.6, 98.3), "ubremen-cartesium-demo4": (87.8, 89.6)}
print("| map | IPA P micro (ROSE2) | IPA R micro (ROSE2) | rooms F1 at IoU 0.5 | segments / true rooms | s |")
print("|---|---|---|---|---|---|")
p_all, r_all, f_all, met = [], [], [], 0
for m in maps:
    j = json.load(open(f"{out}/{m}.json"))
    p, r = 100 * j["ipa"]["precision_micro"], 100 * j["ipa"]["recall_micro"]
    f = 100 * (j["room_match"]["f1"] or 0.0)
    p_all.append(p); r_all.append(r); f_all.append(f)
    ok = p >= rose[m][0] and r >= rose[m][1]
    met += ok
    print(f"| {m} | {p:.1f} ({rose[m][0]:.1f}) | {r:.1f} ({rose[m][1]:.1f}) | {f:.1f} | "
          f"{j['room_match']['segments']} / {j['room_match']['truth_rooms']} | {j['seconds']:.1f} |")
print(f"| median | {statistics.median(p_all):.1f} ({statistics.median(v[0] for v in rose.values()):.1f}) | "
      f"{statistics.median(r_all):.1f} ({statistics.median(v[1] for v in rose.values()):.1f}) | "
      f"{statistics.median(f_all):.1f} | | |")
print(f"\nmaps with both IPA figures at least ROSE2's: {met} of {len(maps)}")
PY
