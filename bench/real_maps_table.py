#!/usr/bin/env python3
"""Per-case table of a `tsgraphs suite suites/real-maps.yaml` run beside ROSE2's published
figures for the same maps (../shared/data/floorplans/README.md), and the medians per method.
Usage: bench/real_maps_table.py RUN_DIR   (the suite's --out folder, read: RUN_DIR/suite.csv)"""
import csv
import statistics
import sys

# ROSE2's IPA micro precision and recall, % (goldleaf3i/declutter-reconstruct, "evaluation4 geometric.txt").
ROSE2 = {"g4s_y2": (91.7, 94.3), "map17": (79.8, 91.3), "map23": (88.8, 97.7), "map_with_clutter": (67.9, 85.3),
         "photo_2020": (91.6, 98.3), "ubremen-cartesium-demo4": (87.8, 89.6)}


def number(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return None


def text(value, scale=1.0, digits=2):
    return "-" if value is None else f"{scale * value:.{digits}f}"


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: real_maps_table.py RUN_DIR")
    rows = [r for r in csv.DictReader(open(f"{sys.argv[1]}/suite.csv")) if r["status"] == "done"]
    print("| map | method | rooms F1 | IPA P / R micro, % (ROSE2's) | f_re | final / visited rooms | unsupported |")
    print("|---|---|---|---|---|---|---|")
    per_method = {}
    for r in rows:
        name = r["case"].removeprefix("import-")
        p, rc = number(r, "rooms_gt.ipa_precision_micro"), number(r, "rooms_gt.ipa_recall_micro")
        rose = ROSE2.get(name)
        print(f"| {name} | {r['method']} | {text(number(r, 'rooms_gt.f1'))} | {text(p, 100, 1)} / {text(rc, 100, 1)}"
              f"{f' ({rose[0]:.1f} / {rose[1]:.1f})' if rose else ''} | {text(number(r, 'consistency.f_re'))} | "
              f"{r['rooms_gt.n_rooms_final']} / {r['rooms_gt.n_truth_visited']} | {r['rooms_gt.unsupported']} |")
        m = per_method.setdefault(r["method"], {"f1": [], "p": [], "r": [], "f_re": []})
        for key, value in (("f1", number(r, "rooms_gt.f1") or 0.0), ("p", p), ("r", rc),
                           ("f_re", number(r, "consistency.f_re") or 0.0)):
            if value is not None:
                m[key].append(value)
    print()
    for method, m in per_method.items():
        med = {k: statistics.median(v) if v else None for k, v in m.items()}
        print(f"{method}: median rooms F1 {text(med['f1'])}, IPA P / R micro {text(med['p'])} / {text(med['r'])}, "
              f"f_re {text(med['f_re'])} ({len(m['f1'])} cases)")


if __name__ == "__main__":
    main()
