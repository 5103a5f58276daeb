#!/usr/bin/env bash
# Set up, build and run the whole test suite: the release build, then the same suite under
# AddressSanitizer and UndefinedBehaviorSanitizer (the asan preset).
# Usage: scripts/test.sh [preset...]   (default: release asan)
set -euo pipefail
cd "$(dirname "$0")/.."
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(release asan)
bash scripts/setup.sh
for preset in "${presets[@]}"; do
  echo "== $preset"
  bash scripts/build.sh "$preset"
  ctest --preset "$preset" -j "$(nproc)"
done
