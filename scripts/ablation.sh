#!/usr/bin/env bash
# Reproduces the ablation table of docs/statistical.md: statistical+ with each of its improvements
# switched off in turn, beside VFC, CHC, CHC++ and Ideal, on the default teapots, the paper library
# and the paper plant. Each scene interleaved in one run, so ratios within a run are fair, and run
# twice, so that the spread stands beside the means (scripts/results_table.py makes the table).
# Run it on a quiet machine. Extra arguments are passed to occsim bench (e.g. --frames 60,
# --deterministic-latency 8).
# Usage: scripts/ablation.sh [occsim bench options...]
#
# Rows "statistical+ KEY=off": statistical+ itself, then one row per mechanism its options
# descriptor marks switchable (ready_answers, virtual_leaves, object_queries, cost_model,
# requery_parallax = 0: BASE_TIME seconds instead, fallback), each switched off alone.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release occsim
source scripts/core_dumps.sh  # a crash leaves a core (and says where)
for scenario in scenarios/teapots.json scenarios/paper/library.json scenarios/paper/plant.json; do
  name=$(basename "$scenario" .json)
  for run in 1 2; do
    echo "== $scenario, run $run ($(uptime))"
    ./build/release/sim/occsim bench "$scenario" --algos vfc,statistical+,chc,chc++,ideal \
      --ablate statistical+ --out "out/ablation/$name/run-$run" "$@"
  done
done
command -v python3 >/dev/null || { echo "ablation.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
python3 scripts/results_table.py out/ablation
