#!/usr/bin/env bash
# Installs the Debian packages tsgraphs needs, only those that are missing.
# Idempotent: when everything is present it installs nothing and touches no package list.
# Usage: bash scripts/install-deps.sh [--sanitize]   (--sanitize: also clang with its sanitizer
# and libFuzzer runtimes, for scripts/sanitize.sh and scripts/fuzz.sh)
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev        # linear algebra, poses
  libpcl-dev           # point-cloud filters, kd-trees, registration
  liblzf-dev           # PCD binary_compressed blocks
  liblz4-dev libzstd-dev zlib1g-dev   # MCAP chunks (lz4 frames, zstd) and CRC32s
  libsqlite3-dev       # rosbag2 SQLite (.db3) recordings
  libceres-dev         # factor-graph back-end
  libnanoflann-dev     # small kd-trees
  robin-map-dev        # the LiDAR odometry's voxel hash map (tsl::robin_map, as KISS-ICP)
  libtbb-dev           # parallel loops (ray casting)
  libembree-dev        # ray casting in the simulator (Embree 3)
  libyaml-cpp-dev      # scene and parameter files
  libpng-dev           # PNG occupancy maps and room labels (import-map)
  libcli11-dev         # command line
  nlohmann-json3-dev   # JSON outputs
  libspdlog-dev        # logging
  librosbag-storage-dev libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libtf2-msgs-dev
  libroscpp-core-dev   # ROS1 bags without a ROS runtime
  libgtest-dev libgmock-dev   # tests
  libbenchmark-dev     # benchmarks
  chromium             # headless, to check that the HTML reports render (tests)
  clang-format python3 # the code's layout and its functions' length (tests: format_check, long_functions)
)
if [ "${1:-}" = "--sanitize" ]; then
  PACKAGES+=(clang libclang-rt-dev)   # ASan, UBSan and libFuzzer builds
elif [ $# -gt 0 ]; then
  echo "install-deps: unknown argument '$1' (the only option is --sanitize)" >&2
  exit 2
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
