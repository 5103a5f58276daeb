#!/usr/bin/env bash
# Set up, build and run the whole test suite. Usage: scripts/test.sh [preset] (release or asan)
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
bash scripts/setup.sh
bash scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"
