#!/usr/bin/env bash
# The shadow-pass tables of docs/views.md: the paper's city and the three game levels under a
# low and a high sun (`--sun`), the shadow pass's casters culled by the light's box
# (light-frustum), by the camera's receivers (`--shadow-casters receivers`), by each culler in
# the light's view (`--shadow-casters culler`) and by both (`culler+receivers`, the "both" views),
# each run twice beside a run without a sun, error measured. VFC culls the camera's view in the runs without a sun and with receiver masking; the
# light-frustum, culler and both runs compare the cullers of --algos (each culls the camera's
# view, and in the culler and both runs the light's view too). Run it on a quiet machine (no build, test or other
# benchmark beside it): each run's summary gives the load before and after.
# Usage: scripts/views_table.sh [--frames N] [--map TEXELS] [--scenes "A.json B.json"]
#                               [--views "none low-frustum ..."] [--algos A,B]
#                               [more occsim bench options...]
#   --frames N: frames a run (default 60); --map: the shadow map's side (default 2048);
#   --scenes: these scenario files instead of the four (one scene a command keeps each command
#   within 15 minutes). The suns: low 15 degrees up, high 60, both from azimuth 40 (LOW_SUN,
#   HIGH_SUN below). --views: only these of none, {low,high}-{frustum,receivers,culler,both}.
#   --algos: the cullers of the light-frustum, culler and both runs (default
#   vfc,statistical,chc,conditional). --out DIR: the runs and tables there (default out/views).
# Output: <out>/<scene>/<view>/run-<n>/{summary.json,frames.csv,report.md}, then the tables
# of every scene under <out> (scripts/views_table.py) and how long it took.
set -euo pipefail
cd "$(dirname "$0")/.."
LOW_SUN=15,40
HIGH_SUN=60,40
algos_compared=vfc,statistical,chc,conditional
views="none low-frustum low-receivers low-culler low-both high-frustum high-receivers high-culler high-both"
frames=60
map=2048
out=out/views
scenes="scenarios/paper/city.json scenarios/levels/courtyards.json scenarios/levels/canyon.json scenarios/levels/interior.json"
bench_args=()
while (($#)); do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --frames=*) frames=${1#--frames=}; shift ;;
    --map) map=$2; shift 2 ;;
    --map=*) map=${1#--map=}; shift ;;
    --scenes) scenes=$2; shift 2 ;;
    --views) views=$2; shift 2 ;;
    --algos) algos_compared=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) bench_args+=("$1"); shift ;;
  esac
done
bash scripts/setup.sh
bash scripts/build.sh release occsim
command -v python3 >/dev/null || { echo "views_table.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
start=$SECONDS
for scene in $scenes; do
  name=$(basename "$scene" .json)
  for run in 1 2; do
    for view in $views; do
      view_args=()
      case $view in
        none|low-frustum|low-receivers|low-culler|low-both) ;;
        high-frustum|high-receivers|high-culler|high-both) ;;
        *) echo "views_table.sh: --views: unknown view '$view'" >&2; exit 2 ;;
      esac
      casters=${view#*-}
      [[ $casters == both ]] && casters=culler+receivers
      case $view in
        low-*) view_args=(--sun "$LOW_SUN,$map" --shadow-casters "$casters") ;;
        high-*) view_args=(--sun "$HIGH_SUN,$map" --shadow-casters "$casters") ;;
      esac
      algos=vfc
      case $view in *-frustum|*-culler|*-both) algos=$algos_compared ;; esac
      echo "== $scene, $view, run $run ($(uptime))"
      ./build/release/sim/occsim bench "$scene" --algos "$algos" --error --quiet --frames "$frames" \
        "${view_args[@]}" --out "$out/$name/$view/run-$run" "${bench_args[@]}" >/dev/null
    done
  done
done
python3 scripts/views_table.py "$out"
echo "== $((SECONDS - start)) s ($(uptime))"
