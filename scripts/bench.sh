#!/usr/bin/env bash
# The main job: set up, build, and benchmark the default scenario headless with every algorithm,
# measuring image error against ground truth. Extra arguments go to `occsim bench`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release occsim
source scripts/core_dumps.sh  # a crash leaves a core (and says where)
exec ./build/release/sim/occsim bench scenarios/teapots.json --error "$@"
