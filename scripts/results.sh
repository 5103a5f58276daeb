#!/usr/bin/env bash
# Reproduces docs/results.md: every scenario in scenarios/paper benchmarked with every algorithm,
# error measured, plots written. About 5 minutes per scenario on a 2-core machine.
# Usage: scripts/results.sh [scenario-name...]   (default: teapots city library plant)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release occsim
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(teapots city library plant)
for name in "${names[@]}"; do
  echo "== scenarios/paper/$name.json"
  ./build/release/sim/occsim bench "scenarios/paper/$name.json" --error --plots \
    --out "out/results/$name"
done
