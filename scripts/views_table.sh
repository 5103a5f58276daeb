#!/usr/bin/env bash
# The shadow-pass table of docs/views.md: the paper's city and the three game levels under a low
# and a high sun (`--sun`), each run twice beside a run without a sun, VFC culling the camera's
# view and light-frustum culling the shadow pass, error measured. Run it on a quiet machine (no
# build, test or other benchmark beside it): each run's summary gives the load before and after.
# Usage: scripts/views_table.sh [--frames N] [--map TEXELS] [more occsim bench options...]
#   --frames N: frames a run (default 60); --map: the shadow map's side (default 2048).
#   The suns: low 15 degrees up, high 60, both from azimuth 40 (LOW_SUN, HIGH_SUN below).
# Output: out/views/<scene>/{none,low,high}/run-<n>/{summary.json,frames.csv,report.md}, then the
# table (scripts/views_table.py) and how long it took.
set -euo pipefail
cd "$(dirname "$0")/.."
LOW_SUN=15,40
HIGH_SUN=60,40
frames=60
map=2048
bench_args=()
while (($#)); do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --frames=*) frames=${1#--frames=}; shift ;;
    --map) map=$2; shift 2 ;;
    --map=*) map=${1#--map=}; shift ;;
    *) bench_args+=("$1"); shift ;;
  esac
done
bash scripts/setup.sh
bash scripts/build.sh release occsim
command -v python3 >/dev/null || { echo "views_table.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
out=out/views
start=$SECONDS
for scene in scenarios/paper/city.json scenarios/levels/courtyards.json \
  scenarios/levels/canyon.json scenarios/levels/interior.json; do
  name=$(basename "$scene" .json)
  for run in 1 2; do
    for sun in none low high; do
      sun_args=()
      [[ $sun == low ]] && sun_args=(--sun "$LOW_SUN,$map")
      [[ $sun == high ]] && sun_args=(--sun "$HIGH_SUN,$map")
      echo "== $scene, sun $sun, run $run ($(uptime))"
      ./build/release/sim/occsim bench "$scene" --algos vfc --error --quiet --frames "$frames" \
        "${sun_args[@]}" --out "$out/$name/$sun/run-$run" "${bench_args[@]}" >/dev/null
    done
  done
done
python3 scripts/views_table.py "$out"
echo "== $((SECONDS - start)) s ($(uptime))"
