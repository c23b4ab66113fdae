#!/usr/bin/env bash
# Generated buildings walked by a person carrying an os-class sensor at 1.5 m, 10 Hz sweeps
# kept at 2 Hz (the carriers suite's hand2 platform), as sequence folders for bench_odometry:
# the LiDAR odometry's development set of issue 16's sixth sitting (seeds 3-5; the carriers
# suite's seeds 1-2 are held out).
#   bench/handheld_walks.sh OUT_DIR [SEEDS...]      (default seeds: 3 4 5; ~1 GB per walk)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="${TSGRAPHS:-$here/build/tsgraphs}"
out="${1:?usage: bench/handheld_walks.sh OUT_DIR [SEEDS...]}"
shift
seeds=("$@")
[ $# -gt 0 ] || seeds=(3 4 5)
mkdir -p "$out/scenes" "$out/seq"
for style in office atrium library irregular mixed; do
  for seed in "${seeds[@]}"; do
    name="$style-s$seed-hand2"
    [ -f "$out/seq/$name/times.txt" ] && continue
    "$bin" -q generate --style "$style" --seed "$seed" --out "$out/scenes/$name.yaml"
    # The generated sensor block (preset, mount height) becomes the carriers' hand2 platform.
    python3 - "$out/scenes/$name.yaml" <<'PY'
import re, sys
path = sys.argv[1]
text = open(path).read()
text, n = re.subn(r"(sensor:\n  preset: \S+\n)  mount_height: \S+\n",
                  r"\1  record_hz: 2\n  mount_height: 1.5\n\nplatform:\n  type: handheld\n  bob: 0.03\n"
                  r"  step_hz: 1.8\n  sway_deg: 4\n  yaw_jitter_deg: 3\n  vibration: 0\n  vibration_hz: 0\n"
                  r"  motion_distortion: true\n", text)
if n != 1:
    sys.exit(path + ": no sensor block to replace")
open(path, "w").write(text)
PY
    "$bin" -q simulate "$out/scenes/$name.yaml" --out "$out/seq/$name"
  done
done
