#!/usr/bin/env bash
# Reproduces the ablation table of docs/statistical.md: statistical+ with each of its improvements
# switched off in turn, beside VFC, CHC++ and Ideal, on the default teapots and the paper library.
# One interleaved run per scene, so ratios within a table are fair. Extra arguments are passed to
# occsim bench (e.g. --frames 100, --deterministic-latency 8, --repetitions 3).
# Usage: scripts/ablation.sh [occsim bench options...]
#
# Rows "statistical+ KEY=off": statistical+ itself, then one row per mechanism its options
# descriptor marks switchable (ready_answers, virtual_leaves, object_queries, cost_model,
# requery_parallax = 0: BASE_TIME seconds instead, fallback), each switched off alone.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release occsim
for scenario in scenarios/teapots.json scenarios/paper/library.json; do
  name=$(basename "$scenario" .json)
  echo "== $scenario"
  ./build/release/sim/occsim bench "$scenario" --algos vfc,statistical+,chc++,ideal \
    --ablate statistical+ --out "out/ablation/$name" "$@"
done
