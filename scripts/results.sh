#!/usr/bin/env bash
# The tables of docs/results.md: every scene of a set benchmarked with every algorithm, error
# measured, twice (two separate runs, so that the run-to-run spread can stand beside the means).
# Each run's console header gives the load average before and after it; run this on a quiet
# machine (no build, test or other benchmark beside it): a run on a busy one says so and is not a
# result. About 5 minutes per scene and run on a 2-core machine with --frames 100.
# Usage: scripts/results.sh [paper|general|default] [occsim bench options...]
#   paper:   scenarios/paper/{teapots,city,library,plant}.json (the default set)
#   general: scenarios/general/*.json (the generalisation set)
#   default: scenarios/teapots.json
# Output: out/results/<set>/<scene>/run-<n>/{summary.json,frames.csv,report.md}
set -euo pipefail
cd "$(dirname "$0")/.."
set_name=${1:-paper}
shift || true
case "$set_name" in
  paper) scenes=(scenarios/paper/teapots.json scenarios/paper/city.json scenarios/paper/library.json
                 scenarios/paper/plant.json) ;;
  general) scenes=(scenarios/general/*.json) ;;
  default) scenes=(scenarios/teapots.json) ;;
  *) echo "results.sh: unknown set '$set_name'; expected paper, general or default" >&2; exit 2 ;;
esac
bash scripts/setup.sh
bash scripts/build.sh release occsim
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .json)
  for run in 1 2; do
    echo "== $scene, run $run ($(uptime))"
    ./build/release/sim/occsim bench "$scene" --error --out "out/results/$set_name/$name/run-$run" "$@"
  done
done
