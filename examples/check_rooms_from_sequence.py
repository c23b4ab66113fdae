#!/usr/bin/env python3
"""ctest's example_rooms_from_sequence: simulates the built-in office, runs the example and
`tsgraphs run` on it, and checks that the example prints the run's rooms (id, kind, level,
walls, centre). Usage: check_rooms_from_sequence.py EXAMPLE TSGRAPHS WORK_DIR"""
import json
import pathlib
import re
import shutil
import subprocess
import sys



def centroid(polygon):
    """The area centroid of a polygon given as [[x, y, ...], ...]."""
    a = cx = cy = 0.0
    for (x0, y0, *_), (x1, y1, *_) in zip(polygon, polygon[1:] + polygon[:1]):
        cross = x0 * y1 - x1 * y0
        a += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    return cx / (3 * a), cy / (3 * a)


example, tsgraphs, work = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
subprocess.run([tsgraphs, "-q", "simulate", "office", "--out", str(work / "seq")], check=True)
subprocess.run([tsgraphs, "-q", "run", str(work / "seq"), "--out", str(work / "run")], check=True)
printed = subprocess.run([example, str(work / "seq")], check=True, capture_output=True, text=True).stdout
print(printed)

line = re.compile(r"^(room|corridor) (\d+): level (-?\d+), centre \((\S+), (\S+)\) m, (\S+) m\^2, (\d+) walls$")
rooms = {}
for text in printed.splitlines()[1:]:
    m = line.match(text)
    assert m, f"unexpected line: {text!r}"
    rooms[int(m.group(2))] = (m.group(1), int(m.group(3)), float(m.group(4)), float(m.group(5)), int(m.group(7)))
graph = json.loads((work / "run" / "scene_graph.json").read_text())
assert rooms, "the example printed no room"
assert len(rooms) == len(graph["rooms"]), f"{len(rooms)} rooms printed, the run has {len(graph['rooms'])}"
for r in graph["rooms"]:
    kind, level, x, y, walls = rooms[r["id"]]
    assert (kind, level, walls) == (r["kind"], r["level"], len(r["walls"])), f"room {r['id']} differs"
    cx, cy = centroid(r["polygon"]) if "polygon" in r else r["rect"]["center"]
    assert abs(x - cx) < 0.01 and abs(y - cy) < 0.01, f"room {r['id']}: ({x}, {y}) against ({cx}, {cy})"
print(f"example: {len(rooms)} rooms, as `tsgraphs run` maps them")
