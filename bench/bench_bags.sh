#!/usr/bin/env bash
# Bag reading speed in each format and compression, in one run (docs/benchmarks.md): one lap of
# a built-in scene (default atrium: os1-64 at 10 Hz) simulated once, written as ROS 1 bags (none,
# lz4, bz2), a rosbag2 SQLite file and rosbag2 MCAP files (none, lz4, zstd), each read by
# bench_bag_read on one thread after the page cache is warmed. Usage: bench/bench_bags.sh [SCENE]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"
scene="${1:-atrium}"
tmp="${TMPDIR:-/tmp}/tsgraphs-bench-bags/$scene"
mkdir -p "$tmp"
if [ ! -f "$tmp/seq/times.txt" ]; then "$bin" -q simulate "$scene" --laps 1 --out "$tmp/seq"; fi
"$here/build/bench/bench_bag_read" --from "$tmp/seq" --to "$tmp" > /dev/null  # writes the bags once
cat "$tmp"/*.bag "$tmp"/*.db3 "$tmp"/*.mcap > /dev/null
taskset -c 0 "$here/build/bench/bench_bag_read" "$tmp"/ros1_*.bag "$tmp"/ros2_*
