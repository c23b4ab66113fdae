#!/usr/bin/env python3
"""T_PGO of a suite folder split by what asked for each solve, per method: loops taken in by a
full or a local solve, periodic full solves, scheduled local solves, the final solve.
Usage: python3 bench/solve_kinds.py SUITE_OUT_DIR   (a `tsgraphs suite` --out folder)"""
import csv
import os
import sys

KINDS = [("loop, full", lambda r, f: r == "loop" and f == "1"), ("loop, local", lambda r, f: r == "loop" and f == "0"),
         ("periodic", lambda r, f: r == "periodic"), ("schedule", lambda r, f: r == "schedule"),
         ("final", lambda r, f: r == "final")]


def main(suite):
    totals = {}
    cases = sorted(os.listdir(os.path.join(suite, "cases")))
    for case in cases:
        for method in sorted(os.listdir(os.path.join(suite, "cases", case))):
            path = os.path.join(suite, "cases", case, method, "timings.csv")
            if not os.path.isfile(path):
                continue
            count, secs = totals.setdefault(method, ([0] * len(KINDS), [0.0] * len(KINDS)))
            for row in csv.DictReader(open(path)):
                if row["kind"] != "optimization":
                    continue
                for i, (_, match) in enumerate(KINDS):
                    if match(row["reason"], row["full"]):
                        count[i] += 1
                        secs[i] += float(row["optimization_s"])
    print("method".ljust(16) + "".join(k.rjust(24) for k, _ in KINDS) + "total s".rjust(10))
    for method, (count, secs) in sorted(totals.items()):
        cells = "".join(f"  {n} / {s:.1f} s ({1000 * s / max(n, 1):.1f} ms)".rjust(24) for n, s in zip(count, secs))
        print(method.ljust(16) + cells + f"{sum(secs):10.1f}")


if __name__ == "__main__":
    main(sys.argv[1])
