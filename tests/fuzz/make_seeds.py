#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (corpus/<target>/): small valid inputs of every format
each reader takes, so the fuzzers start from files that get past the first checks.
Usage: python3 tests/fuzz/make_seeds.py TSGRAPHS_BINARY [TARGET...]  (from the repository's root;
TARGETs, among those STANDALONE lists, rewrite only their corpora)
The bags and scans come from `tsgraphs simulate` on tiny.yaml (2 x 8 beams); the rest is
written here from the formats' definitions (standard library only)."""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.getcwd()
HERE = os.path.join(ROOT, "tests", "fuzz")
CORPUS = os.path.join(HERE, "corpus")


def put(target, name, data):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    with open(os.path.join(CORPUS, target, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


POINTS = [(1.0 + 0.25 * i, -0.5 * i, 0.1 * (i % 3), float(i)) for i in range(6)]


def pcd_header(fields, sizes, types, counts, n, data):
    return (f"# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {fields}\nSIZE {sizes}\n"
            f"TYPE {types}\nCOUNT {counts}\nWIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA {data}\n")


def lzf_literals(raw):
    """LZF with literal runs only (a control byte c < 32, then c + 1 bytes): valid for any decoder."""
    out = bytearray()
    for i in range(0, len(raw), 32):
        piece = raw[i:i + 32]
        out.append(len(piece) - 1)
        out += piece
    return bytes(out)


def pcd_seeds():
    n = len(POINTS)
    ascii_body = "".join(f"{x} {y} {z} {i}\n" for x, y, z, i in POINTS)
    put("pcd", "ascii.pcd", pcd_header("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1", n, "ascii") + ascii_body)
    binary = b"".join(struct.pack("<4f", *p) for p in POINTS)
    put("pcd", "binary.pcd", pcd_header("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1", n, "binary").encode() + binary)
    xyz_double = b"".join(struct.pack("<3d", *p[:3]) for p in POINTS)
    put("pcd", "binary_double.pcd", pcd_header("x y z", "8 8 8", "F F F", "1 1 1", n, "binary").encode() + xyz_double)
    # binary_compressed stores the fields one after another (all x, then all y, ...).
    soa = b"".join(struct.pack(f"<{n}f", *[p[k] for p in POINTS]) for k in range(4))
    lzf = lzf_literals(soa)
    put("pcd", "binary_compressed.pcd",
        pcd_header("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1", n, "binary_compressed").encode()
        + struct.pack("<II", len(lzf), len(soa)) + lzf)


def kitti_seeds(seq):
    with open(os.path.join(seq, "scans", "000000.bin"), "rb") as f:
        put("kitti", "000000.bin", f.read())
    rows = []
    for k in range(3):
        rows.append(" ".join(f"{v:.6e}" for v in [1, 0, 0, 0.1 * k, 0, 1, 0, 0, 0, 0, 1, 0]))
    put("kitti", "poses.txt", "\n".join(rows) + "\n")
    with open(os.path.join(seq, "times.txt")) as f:
        put("kitti", "times.txt", "".join(f.readlines()[:4]))


def tum_seeds(seq):
    with open(os.path.join(seq, "odom.txt")) as f:
        put("tum", "odom.txt", "".join(f.readlines()[:4]))
    put("tum", "commented.txt", "# timestamp tx ty tz qx qy qz qw\n0.0 0 0 0 0 0 0 1\n0.1 0.1 0 0 0 0 0.0499792 0.9987503\n")


def ros_string(s):
    return struct.pack("<I", len(s)) + s.encode()


def point_cloud2_seeds():
    def message(fields, point_step, points, bigendian=0, height=1):
        body = struct.pack("<III", 7, 100, 5000) + ros_string("lidar")
        body += struct.pack("<II", height, len(points) // height) + struct.pack("<I", len(fields))
        for name, offset, datatype, count in fields:
            body += ros_string(name) + struct.pack("<IBI", offset, datatype, count)
        data = b"".join(points)
        body += struct.pack("<BII", bigendian, point_step, point_step * len(points) // height)
        return body + struct.pack("<I", len(data)) + data + b"\x01"
    xyzi = [("x", 0, 7, 1), ("y", 4, 7, 1), ("z", 8, 7, 1), ("intensity", 12, 7, 1)]
    put("point_cloud2", "xyzi.msg", message(xyzi, 16, [struct.pack("<4f", *p) for p in POINTS]))
    padded = [("x", 0, 8, 1), ("y", 8, 8, 1), ("z", 16, 8, 1), ("t", 24, 7, 1), ("ring", 28, 4, 1)]
    put("point_cloud2", "double_time_ring.msg",
        message(padded, 32, [struct.pack("<3dfH2x", *p[:3], 0.01 * k, k % 2) for k, p in enumerate(POINTS)]))
    put("point_cloud2", "organised.msg", message(xyzi, 16, [struct.pack("<4f", *p) for p in POINTS], height=2))


def png(width, height, rows, colour_type=0):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"".join(b"\x00" + row for row in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def occupancy_map_seeds():
    grey = [bytes([0 if x in (0, 7) or y in (0, 5) else 254 for x in range(8)]) for y in range(6)]
    put("occupancy_map", "map.png", png(8, 6, grey))
    rgba = [b"".join(bytes([v, v, v, 255]) for v in row) for row in grey]
    put("occupancy_map", "map_rgba.png", png(8, 6, rgba, colour_type=6))
    put("occupancy_map", "map.pgm", b"P5\n8 6\n255\n" + b"".join(grey))
    put("occupancy_map", "map.yaml",
        "image: map.png\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n")


def run_folder_seeds(run):
    graph = json.load(open(os.path.join(run, "scene_graph.json")))
    for key, value in graph.items():
        if isinstance(value, list):
            graph[key] = value[:3]
    for room in graph.get("rooms", []):  # a room's own lists (free space, outline) cut short too
        for key, value in room.items():
            if isinstance(value, list) and len(value) > 4 and isinstance(value[0], list):
                room[key] = value[:4]
    put("run_folder", "scene_graph.json", json.dumps(graph, indent=1))
    with open(os.path.join(run, "rooms_events.jsonl")) as f:
        put("run_folder", "rooms_events.jsonl", "".join(f.readlines()[:4]))
    with open(os.path.join(run, "timings.csv")) as f:
        lines = f.readlines()
    scans = [l for l in lines[1:] if l.startswith("scan")][:3]
    solves = [l for l in lines[1:] if not l.startswith("scan")][:2]
    put("run_folder", "timings.csv", "".join([lines[0]] + scans + solves))
    with open(os.path.join(run, "run_info.json")) as f:
        put("run_folder", "run_info.json", f.read())


def mcap_file(compression, chunk_messages=3, messages=7, summary=True, crcs=True):
    """An MCAP (mcap.dev/spec): two channels, messages in chunks of chunk_messages with their
    message indexes, a Data End with the data CRC, a summary (schemas, channels, chunk indexes,
    statistics) with summary offsets and its CRC. Chunks are compressed by the zstd or lz4 command.
    Without crcs every CRC is 0 (not checked), so that mutations reach the fields behind them."""
    crc32 = zlib.crc32 if crcs else (lambda b: 0)
    u16, u32, u64 = (lambda v: struct.pack("<H", v)), (lambda v: struct.pack("<I", v)), (lambda v: struct.pack("<Q", v))
    string = lambda b: u32(len(b)) + b
    record = lambda op, content: bytes([op]) + u64(len(content)) + content
    magic = b"\x89MCAP0\r\n"
    schema = record(0x03, u16(1) + string(b"pkg/msg/A") + string(b"ros2msg") + string(b"int32 a\n"))
    channels = [record(0x04, u16(c) + u16(1) + string(b"/t%d" % c) + string(b"cdr") + u32(0)) for c in (1, 2)]
    out = magic + record(0x01, string(b"ros2") + string(b"seeds"))
    chunk_indexes = []
    for first in range(0, messages, chunk_messages):
        records = schema + b"".join(channels) if first == 0 else b""
        index = {}
        for i in range(first, min(first + chunk_messages, messages)):
            channel = 1 + i % 2
            index.setdefault(channel, []).append((100 + i, len(records)))
            records += record(0x05, u16(channel) + u32(i) + u64(100 + i) + u64(100 + i) + bytes([i]) * (3 + i))
        packed = records
        if compression:
            packed = subprocess.run([compression, "-c", "-q"], input=records, check=True, capture_output=True).stdout
        times = [t for entries in index.values() for t, _ in entries]
        chunk_at = len(out)
        chunk = record(0x06, u64(min(times)) + u64(max(times)) + u64(len(records)) + u32(crc32(records))
                       + string(compression.encode()) + u64(len(packed)) + packed)
        out += chunk
        offsets, indexes_at = b"", len(out)
        for channel in sorted(index):
            offsets += u16(channel) + u64(len(out))
            out += record(0x07, u16(channel) + string(b"".join(u64(t) + u64(o) for t, o in index[channel])))
        chunk_indexes.append(record(0x08, u64(min(times)) + u64(max(times)) + u64(chunk_at) + u64(len(chunk))
                                    + string(offsets) + u64(len(out) - indexes_at) + string(compression.encode())
                                    + u64(len(packed)) + u64(len(records))))
    out += record(0x0F, u32(crc32(out)))
    summary_start, summary_offsets = len(out), b""
    if summary:
        stats = record(0x0B, u64(messages) + u16(1) + u32(2) + u32(0) + u32(0) + u32(len(chunk_indexes)) + u64(100)
                       + u64(100 + messages - 1) + string(b""))
        for op, group in ((0x03, schema), (0x04, b"".join(channels)), (0x08, b"".join(chunk_indexes)), (0x0B, stats)):
            summary_offsets += record(0x0E, bytes([op]) + u64(len(out)) + u64(len(group)))
            out += group
    offsets_start = len(out)
    out += summary_offsets
    footer = bytes([0x02]) + u64(20) + u64(summary_start if summary else 0) + u64(offsets_start if summary else 0)
    crc = crc32(out[summary_start:] + footer) if summary else 0
    return out + footer + u32(crc) + magic


def mcap_seeds():
    for compression in ("", "zstd", "lz4"):
        put("mcap", f"chunked_{compression or 'none'}.mcap", mcap_file(compression))
    put("mcap", "no_summary.mcap", mcap_file("", summary=False))
    put("mcap", "one_chunk.mcap", mcap_file("zstd", chunk_messages=100, messages=3))
    put("mcap", "no_crcs.mcap", mcap_file("", crcs=False))
    put("mcap", "no_crcs_no_summary.mcap", mcap_file("", summary=False, crcs=False))


class Cdr:
    """Little-endian CDR (XCDR1): each value aligned to its size, counted after the 4-byte header."""
    def __init__(self):
        self.body = bytearray()

    def put(self, fmt, value):
        size = struct.calcsize("<" + fmt)
        self.body += b"\0" * (-len(self.body) % size)
        self.body += struct.pack("<" + fmt, value)

    def string(self, s):
        self.put("I", len(s) + 1)
        self.body += s.encode() + b"\0"

    def bytes(self):
        return b"\x00\x01\x00\x00" + bytes(self.body)


def ros2_message_seeds():
    def header(c, frame):
        c.put("i", 12), c.put("I", 500000000), c.string(frame)
    def pose(c, xyz, q):
        for v in tuple(xyz) + tuple(q):
            c.put("d", v)
    c = Cdr()
    header(c, "odom"), c.string("base_link"), pose(c, (1, 2, 3), (0, 0, 0.2474, 0.9689))
    for _ in range(36 + 6 + 36):
        c.put("d", 0.0)
    put("ros2_messages", "odometry.cdr", c.bytes())
    c = Cdr()
    header(c, "map"), pose(c, (-1, 0.5, 0), (0, 0, 0, 1))
    put("ros2_messages", "pose_stamped.cdr", c.bytes())
    c = Cdr()
    c.put("I", 2)
    for parent, child in (("base_link", "lidar"), ("map", "odom")):
        header(c, parent), c.string(child), pose(c, (0.1, 0, 0.3), (0, 0, 0, 1))
    put("ros2_messages", "tf_message.cdr", c.bytes())
    c = Cdr()
    header(c, "lidar"), c.put("I", 1), c.put("I", len(POINTS))
    c.put("I", 4)
    for i, name in enumerate(("x", "y", "z", "intensity")):
        c.string(name), c.put("I", 4 * i), c.put("B", 7), c.put("I", 1)
    c.put("B", 0), c.put("I", 16), c.put("I", 16 * len(POINTS))
    c.put("I", 16 * len(POINTS))
    c.body += b"".join(struct.pack("<4f", *p) for p in POINTS)
    c.put("B", 1)
    put("ros2_messages", "point_cloud2.cdr", c.bytes())


def rosbag2_metadata_seeds(tsgraphs, tmp):
    """metadata.yaml as `simulate --bag FOLDER` writes it for a folder named bag (the fuzz target's
    folder holds the files these list): SQLite, MCAP, each under rosbag2's own compression, and a
    split of two files (as rosbag2 writes one, by hand); a file listed twice (under another spelling,
    through a link) makes regression seeds."""
    def metadata(name, bag_format, compression):
        folder = os.path.join(tmp, name, "bag")
        subprocess.run([tsgraphs, "simulate", os.path.join(HERE, "tiny.yaml"), "--bag", folder, "--bag-format", bag_format,
                        "--compression", compression], check=True, capture_output=True)
        with open(os.path.join(folder, "metadata.yaml")) as f:
            return f.read()
    sqlite = metadata("sqlite", "ros2-sqlite", "none")
    put("rosbag2_metadata", "sqlite.yaml", sqlite)
    put("rosbag2_metadata", "mcap.yaml", metadata("mcap", "ros2-mcap", "zstd"))
    put("rosbag2_metadata", "sqlite_zstd_file.yaml", metadata("sqlite_file", "ros2-sqlite", "zstd-file"))
    put("rosbag2_metadata", "mcap_zstd_message.yaml", metadata("mcap_message", "ros2-mcap", "zstd-message"))
    listed = "relative_file_paths:\n    - bag_0.db3\n"
    assert listed in sqlite, sqlite
    put("rosbag2_metadata", "split.yaml", sqlite.replace(listed, listed + "    - bag_1.db3\n"))
    put("rosbag2_metadata", "regression_listed_twice.yaml", sqlite.replace(listed, listed + "    - ./bag_0.db3\n"))
    put("rosbag2_metadata", "regression_listed_through_a_link.yaml", sqlite.replace(listed, listed + "    - link_0.db3\n"))
    # A split with each file's times (rosbag2 >= Humble): the second file after the first, or
    # starting with it (a copy of it, as a regression seed).
    first = re.search(r"  files:\n    - path: bag_0.db3\n.*?nanoseconds: (\d+)\n      message_count: \d+\n", sqlite, re.S)
    assert first, sqlite
    def split_with(start):
        second = "    - path: bag_1.db3\n" + first.group(0).split("- path: bag_0.db3\n", 1)[1].replace(
            "nanoseconds_since_epoch: 0", f"nanoseconds_since_epoch: {start}")
        return sqlite.replace(listed, listed + "    - bag_1.db3\n").replace(first.group(0), first.group(0) + second)
    put("rosbag2_metadata", "split_with_times.yaml", split_with(int(first.group(1))))
    put("rosbag2_metadata", "regression_split_file_repeated.yaml", split_with(0))


def suite_file_seeds():
    """The shipped suites, their import cases naming the fuzz target's map and labels (each by a
    name of its own, as ids must differ), and variants of every kind of case and key."""
    suites = os.path.join(ROOT, "suites")
    for name in sorted(os.listdir(suites)):
        with open(os.path.join(suites, name)) as f:
            text = f.read()
        text = re.sub(r"\{map: [^,]*/([^/,]+)\.yaml, rooms: [^}]*\}", r"{map: map.yaml, rooms: rooms.png, name: \1}", text)
        put("suite_file", name, text)
    put("suite_file", "every_kind.yaml",
        "name: every_kind\nmethods: [ts-graphs, s-graphs-plus, traversable-timer, esdf-flush]\nlaps: 3\ncases:\n"
        "  - generate: {styles: office, seeds: 4, size: 0.5, people: 3, realistic: true}\n"
        "  - generate:\n      styles: [atrium, multi_storey]\n      seeds: \"7-9\"\n      platforms:\n"
        "        - default\n        - {name: low, mount_height: 0.3, preset: vlp-16}\n"
        "        - {name: walk, type: handheld, rate_hz: 10, record_hz: 2}\n"
        "  - import: {map: map.yaml, rooms: rooms.png, ceiling: 3.0, name: floor}\n"
        "  - import: {map: map.yaml}\n"
        "  - scene: office\n"
        "  - scene: two_storeys\n"
        "  - sequence: seq\n")
    put("suite_file", "defaults.yaml", "name: defaults\ncases:\n  - generate: {styles: [library], seeds: [1, 2, 3]}\n")


def pgm(rows):
    return b"P5\n%d %d\n255\n" % (len(rows[0]), len(rows)) + b"".join(bytes(r) for r in rows)


def drawn_map(width, height, resolution, boxes):
    """A map_server image (row 0 at the top) of width x height m: unknown (205) but for `boxes`,
    (x0, y0, x1, y1, value) in m from the lower-left corner, drawn in order."""
    cols, rows = round(width / resolution), round(height / resolution)
    image = [[205] * cols for _ in range(rows)]
    for x0, y0, x1, y1, value in boxes:
        for j in range(rows):
            y = (rows - 1 - j + 0.5) * resolution
            for i in range(cols):
                if x0 <= (i + 0.5) * resolution <= x1 and y0 <= y <= y1:
                    image[j][i] = value
    return image


def map_import_seeds():
    """Small drawn maps as `import-map` reads them: the YAML, a line "...", the image. A room; two
    rooms through a door, moved and turned; the import-map tests' building (tests/map_test_support.hpp)
    at 0.1 m: a corridor, three rooms, a closet behind a narrow door, a void, a stray speck."""
    free, wall = 254, 0
    yaml = "image: map.pgm\nresolution: {res}\norigin: {origin}\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    room = drawn_map(3.5, 2.5, 0.05, [(0.2, 0.2, 3.3, 2.3, wall), (0.3, 0.3, 3.2, 2.2, free)])
    put("map_import", "room.map", (yaml.format(res=0.05, origin="[0.0, 0.0, 0.0]") + "...\n").encode() + pgm(room))
    two = drawn_map(6.5, 3.5, 0.05, [(0.2, 0.2, 6.3, 3.3, wall), (0.3, 0.3, 6.2, 3.2, free), (3.2, 0.3, 3.3, 3.2, wall),
                                     (3.2, 1.2, 3.3, 2.2, free)])
    put("map_import", "two_rooms.map",
        (yaml.format(res=0.05, origin="[-2.0, -1.0, 0.3]") + "mode: scale\n...\n").encode() + pgm(two))
    building = [(1.0, 1.0, 13.0, 9.0, wall), (1.15, 1.15, 12.85, 8.85, free), (1.15, 3.0, 12.85, 3.1, wall),
                (5.0, 3.1, 5.5, 8.85, wall), (9.0, 3.1, 9.1, 8.85, wall), (12.15, 1.15, 12.25, 3.0, wall)]
    doors = [(2.5, 3.0, 3.5, 3.1), (6.5, 3.0, 7.5, 3.1), (10.0, 3.0, 11.0, 3.1), (12.15, 1.8, 12.25, 2.4)]
    building += [d + (free,) for d in doors]
    building += [(10.4, 5.4, 11.6, 6.6, 205), (2.0, 7.5, 2.5, 8.0, 205), (0.2, 0.2, 0.45, 0.45, free)]
    put("map_import", "building.map",
        (yaml.format(res=0.1, origin="[-2.0, -1.0, 0.0]") + "...\n").encode() + pgm(drawn_map(14.0, 10.0, 0.1, building)))
    png_room = png(len(room[0]), len(room), [bytes(r) for r in room])
    put("map_import", "room_png.map", (yaml.format(res=0.05, origin="[5.0, 5.0, -1.5]") + "...\n").encode() + png_room)


def generate_seeds():
    """The generator's options as fuzz_generate.cpp lays them out: style index, seed, size step,
    laps, people, realistic; every style, at the target's largest size (0.3) and below."""
    for style, name in enumerate(("office", "atrium", "library", "open_plan", "irregular", "multi_storey", "mixed")):
        people, realistic = style % 3, style % 2
        size_step = 255 if style % 2 == 0 else 127
        put("generate", f"{name}.bin", struct.pack("<BQBibB", style, style + 1, size_step, 2, people, realistic))


# Corpora written from this script alone: `make_seeds.py TSGRAPHS_BINARY suite_file map_import`
# rewrites only those.
STANDALONE = {"suite_file": suite_file_seeds, "map_import": map_import_seeds, "generate": generate_seeds}


def main():
    if len(sys.argv) < 2 or any(t not in STANDALONE for t in sys.argv[2:]):
        sys.exit(__doc__)
    tsgraphs = os.path.abspath(sys.argv[1])
    if len(sys.argv) > 2:
        for target in sys.argv[2:]:
            shutil.rmtree(os.path.join(CORPUS, target), ignore_errors=True)
            STANDALONE[target]()
        return
    shutil.rmtree(CORPUS, ignore_errors=True)
    with tempfile.TemporaryDirectory() as tmp:
        tiny = os.path.join(HERE, "tiny.yaml")
        seq, run = os.path.join(tmp, "seq"), os.path.join(tmp, "run")
        subprocess.run([tsgraphs, "simulate", tiny, "--out", seq], check=True, capture_output=True)
        for compression in ("none", "bz2", "lz4"):
            bag = os.path.join(tmp, f"{compression}.bag")
            subprocess.run([tsgraphs, "simulate", tiny, "--bag", bag, "--compression", compression],
                           check=True, capture_output=True)
            with open(bag, "rb") as f:
                put("ros_bag", f"{compression}.bag", f.read())
        two_rooms_seq = os.path.join(tmp, "two_rooms")
        subprocess.run([tsgraphs, "simulate", os.path.join(ROOT, "tests", "data", "scenes", "two_rooms.yaml"),
                        "--out", two_rooms_seq], check=True, capture_output=True)
        subprocess.run([tsgraphs, "run", two_rooms_seq, "--out", run], check=True, capture_output=True)
        pcd_seeds()
        mcap_seeds()
        ros2_message_seeds()
        kitti_seeds(seq)
        tum_seeds(seq)
        point_cloud2_seeds()
        occupancy_map_seeds()
        run_folder_seeds(run)
        rosbag2_metadata_seeds(tsgraphs, tmp)
        for write_seeds in STANDALONE.values():
            write_seeds()
        with open(os.path.join(run, "params.yaml")) as f:
            put("params", "run_params.yaml", f.read())
    shutil.copy(os.path.join(ROOT, "config", "params.yaml"), os.path.join(CORPUS, "params", "params.yaml"))
    put("params", "few_keys.yaml", "ground:\n  resolution: 0.5\nroom_loop_closure:\n  enabled: false\nplatform:\n  sensor_height: 1.2\n")
    os.makedirs(os.path.join(CORPUS, "scene"), exist_ok=True)
    for name in ("office.yaml", "two_storeys.yaml"):
        shutil.copy(os.path.join(ROOT, "scenes", name), os.path.join(CORPUS, "scene", name))
    shutil.copy(os.path.join(ROOT, "tests", "data", "scenes", "two_rooms.yaml"), os.path.join(CORPUS, "scene"))
    shutil.copy(os.path.join(HERE, "tiny.yaml"), os.path.join(CORPUS, "scene"))
    subprocess.run([tsgraphs, "generate", "--style", "open_plan", "--seed", "5", "--out",
                    os.path.join(CORPUS, "scene", "open_plan.yaml")], check=True, capture_output=True)


if __name__ == "__main__":
    main()
