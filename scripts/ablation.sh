#!/usr/bin/env bash
# Reproduces the ablation table of docs/statistical.md: statistical+ with each of its improvements
# switched off in turn, beside VFC, CHC++ and Ideal, on the default teapots and the paper library.
# One interleaved run per scene, so ratios within a table are fair. Extra arguments are passed to
# occsim bench (e.g. --frames 100, --deterministic-latency 8, --repetitions 3).
# Usage: scripts/ablation.sh [occsim bench options...]
#
# Rows "statistical+ without=N": 0 = nothing off (statistical+ itself), 1 = ready answers,
# 2 = virtual leaves, 3 = cost model, 4 = re-query by distance (BASE_TIME seconds instead),
# 5 = fallback to frustum culling, 6 = per-object queries.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release occsim
for scenario in scenarios/teapots.json scenarios/paper/library.json; do
  name=$(basename "$scenario" .json)
  echo "== $scenario"
  ./build/release/sim/occsim bench "$scenario" --algos vfc,statistical+,chc++,ideal \
    --sweep without=0,1,2,3,4,5,6 --out "out/ablation/$name" "$@"
done
