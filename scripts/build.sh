#!/usr/bin/env bash
# Configures and builds one preset (default: release), all targets or the ones named.
# Usage: scripts/build.sh [preset] [target...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
shift || true
targets=()
for t in "$@"; do targets+=(--target "$t"); done
# A folder configured before the presets named Ninja (Unix Makefiles) cannot switch generator in
# place: its cache goes, its build outputs stay (Ninja rebuilds what it cannot vouch for).
cache="build/$preset/CMakeCache.txt"
if [ -f "$cache" ] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$cache"; then
  echo "build.sh: build/$preset was configured for another generator; reconfiguring it for Ninja"
  rm -rf "$cache" "build/$preset/CMakeFiles"
fi
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)" "${targets[@]}"
