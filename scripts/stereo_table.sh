#!/usr/bin/env bash
# The stereo table of docs/views.md: the paper's city and the three game levels seen by one eye
# (the camera) and by two eyes culled by one pass over the frustum enclosing both and by an
# instance of each culler per eye (`--stereo SEPARATION,MODE`), each run twice, error measured.
# Run it on a quiet machine (no build, test or other benchmark beside it): each run's summary
# gives the load before and after.
# Usage: scripts/stereo_table.sh [--frames N] [--separation M] [--scenes "A.json B.json"]
#                                [--modes "mono enclosing per_eye"] [--algos A,B]
#                                [more occsim bench options...]
#   --frames N: frames a run (default 60); --separation: metres between the eyes (default
#   0.064); --scenes: these scenario files instead of the four (one scene a command keeps each
#   command within 15 minutes); --modes: only these; --algos: the cullers (default
#   vfc,statistical,chc,conditional).
# Output: out/stereo/<scene>/<mode>/run-<n>/{summary.json,frames.csv,report.md}, then the table of
# every scene under out/stereo (scripts/stereo_table.py) and how long it took.
set -euo pipefail
cd "$(dirname "$0")/.."
algos=vfc,statistical,chc,conditional
modes="mono enclosing per_eye"
frames=60
separation=0.064
scenes="scenarios/paper/city.json scenarios/levels/courtyards.json scenarios/levels/canyon.json scenarios/levels/interior.json"
bench_args=()
while (($#)); do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --frames=*) frames=${1#--frames=}; shift ;;
    --separation) separation=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    --algos) algos=$2; shift 2 ;;
    *) bench_args+=("$1"); shift ;;
  esac
done
bash scripts/setup.sh
bash scripts/build.sh release occsim
command -v python3 >/dev/null || { echo "stereo_table.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
out=out/stereo
start=$SECONDS
for scene in $scenes; do
  name=$(basename "$scene" .json)
  for run in 1 2; do
    for mode in $modes; do
      mode_args=()
      case $mode in
        mono) ;;
        enclosing|per_eye) mode_args=(--stereo "$separation,$mode") ;;
        *) echo "stereo_table.sh: --modes: unknown mode '$mode'" >&2; exit 2 ;;
      esac
      echo "== $scene, $mode, run $run ($(uptime))"
      ./build/release/sim/occsim bench "$scene" --algos "$algos" --error --quiet --frames "$frames" \
        "${mode_args[@]}" --out "$out/$name/$mode/run-$run" "${bench_args[@]}" >/dev/null
    done
  done
done
python3 scripts/stereo_table.py "$out"
echo "== $((SECONDS - start)) s ($(uptime))"
