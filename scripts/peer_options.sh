#!/usr/bin/env bash
# The option tables of docs/results.md for today's peers (hzb, raster, conditional, masked): each option
# of their descriptors switched or swept beside VFC, in one interleaved run per option, error
# measured, every run twice so that the spread stands beside the means. Run it on a quiet machine
# (no build, test or other benchmark beside it); each run's summary gives the load average.
# About 13 minutes per scene with --frames 60 on a 2-core machine for the 10 runs before
# hzb-read_back, raster-node_units and raster-batches joined (not timed since; each run about
# 40 s).
# Usage: scripts/peer_options.sh [SCENARIO...] [-- occsim bench options...]
#   default scenario: scenarios/teapots.json; e.g. scripts/peer_options.sh -- --frames 60
# Output: out/peer-options/<scene>/<option>/run-<n>/, then a table per scene
# (scripts/results_table.py: one row per option, one column per configuration).
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=()
while [[ $# -gt 0 && $1 != -- ]]; do scenes+=("$1"); shift; done
[[ $# -gt 0 ]] && shift  # the --
[[ ${#scenes[@]} -eq 0 ]] && scenes=(scenarios/teapots.json)
# option name | occsim bench flags of its run
runs=(
  "hzb-sphere_bounds|--algos vfc,hzb --sweep hzb:sphere_bounds=false,true"
  "hzb-node_units|--algos vfc,hzb --sweep hzb:node_units=false,true"
  "hzb-read_back|--algos vfc,hzb --sweep hzb:read_back=false,true"
  "raster-node_units|--algos vfc,raster --sweep raster:node_units=false,true"
  "raster-batches|--algos vfc,raster --sweep raster:batches=1,2,4,8"
  "conditional-wait|--algos vfc,conditional --sweep conditional:wait=false,true"
  "conditional-node_queries|--algos vfc,conditional --sweep conditional:node_queries=false,true"
  "masked-width|--algos vfc,masked --sweep masked:width=320,0"
  "masked-cell_width|--algos vfc,masked --sweep masked:cell_width=8,32"
  "masked-drawn_occluders|--algos vfc,masked --sweep masked:drawn_occluders=false,true"
  "masked-simplified_occluders|--algos vfc,masked --sweep masked:simplified_occluders=false,true"
  "masked-occluder_triangles|--algos vfc,masked --sweep masked:occluder_triangles=20000,50000,200000"
  "masked-simd|--algos vfc,masked --sweep masked:simd=false,true"
)
bash scripts/setup.sh
bash scripts/build.sh release occsim
source scripts/core_dumps.sh  # a crash leaves a core (and says where)
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .json)
  for run in 1 2; do
    for entry in "${runs[@]}"; do
      option=${entry%%|*}
      read -r -a flags <<< "${entry#*|}"
      echo "== $scene, $option, run $run ($(uptime))"
      ./build/release/sim/occsim bench "$scene" "${flags[@]}" --error \
        --out "out/peer-options/$name/$option/run-$run" "$@"
    done
  done
done
command -v python3 >/dev/null || { echo "peer_options.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
for scene in "${scenes[@]}"; do
  python3 scripts/results_table.py "out/peer-options/$(basename "$scene" .json)"
done
