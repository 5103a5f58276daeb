#!/usr/bin/env bash
# One paper scene under valgrind's memcheck, a few frames in a small viewport: once per stage
# (docs/stability.md), to look for the intermittent segfault of issue 34 where it can live.
# Unlike AddressSanitizer, memcheck sees the reads and writes made inside Mesa (llvmpipe, OSMesa),
# which are not instrumented: a write into a freed block by the driver shows here and only here.
# Slow (minutes: every instruction is translated), so not in the test suite.
# Usage: scripts/valgrind.sh [SCENE] [FRAMES] [BACKEND]
#   defaults: scenarios/paper/library.json, 3 frames, osmesa where the build has it (else egl)
# Output: out/valgrind/<scene>-<backend>.log (memcheck's report); exit 0 when memcheck found no
# error, 1 when it found some (the log says which), 2 for bad input.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenarios/paper/library.json}
frames=${2:-3}
backend=${3:-}
command -v valgrind >/dev/null || { echo "valgrind.sh: valgrind not found (apt-get install valgrind)" >&2; exit 2; }
[ -f "$scene" ] || { echo "valgrind.sh: $scene: no such scenario file" >&2; exit 2; }
case "$frames" in ''|*[!0-9]*) echo "valgrind.sh: FRAMES: expected a whole number, got '$frames'" >&2; exit 2 ;; esac
bash scripts/build.sh release occsim >/dev/null
source scripts/core_dumps.sh
occsim=./build/release/sim/occsim
if [ -z "$backend" ]; then
  if "$occsim" devices | grep -q "^OSMesa: in this build"; then backend=osmesa; else backend=egl; fi
fi

# The scene with a small viewport: memcheck's cost grows with the pixels llvmpipe fills.
work=$(mktemp -d /tmp/occsim-valgrind.XXXXXX)
trap 'rm -rf "$work"' EXIT
small="$work/$(basename "$scene")"
sed 's/"viewport": *{[^}]*}/"viewport": {"width": 160, "height": 120}/' "$scene" > "$small"
grep -q '"viewport": {"width": 160, "height": 120}' "$small" ||
  { echo "valgrind.sh: $scene: no \"viewport\": {...} on one line to shrink" >&2; exit 2; }

name=$(basename "$scene" .json)
mkdir -p out/valgrind
log="out/valgrind/$name-$backend.log"
echo "valgrind.sh: $scene, $frames frames, 160x120, --backend $backend, every culler, error measured -> $log"
status=0
valgrind --tool=memcheck --error-exitcode=99 --num-callers=40 --log-file="$log" \
  "$occsim" bench "$small" --frames "$frames" --error --deterministic-latency 4 \
  --backend "$backend" --out "$work/out" > "$work/console.txt" 2>&1 || status=$?
case $status in
  0) echo "valgrind.sh: no memcheck error ($(grep -m1 'ERROR SUMMARY' "$log" | sed 's/^==[0-9]*== //'))" ;;
  99) echo "valgrind.sh: memcheck found errors: $(grep -m1 'ERROR SUMMARY' "$log" | sed 's/^==[0-9]*== //'); see $log" >&2
      exit 1 ;;
  *) cat "$work/console.txt" >&2
     echo "valgrind.sh: occsim exited $status under valgrind; see $log" >&2
     exit 1 ;;
esac
