#!/usr/bin/env bash
# The test loop in stages, each with a time budget on a 2-core machine (docs/testing.md):
#   scripts/test.sh quick   the release build of the programs (occsim, occtune) and of the `unit`
#                           tests' executables, and the `unit` tests: the inner loop
#   scripts/test.sh         the README's test command: the release build and every test but the
#                           cluster test, then the `unit` and `gl` tests under ASan + UBSan (the
#                           sanitizer build makes only their executables)
#   scripts/test.sh ci      what .ci/run runs: the README's test command, then the no-osmesa
#                           build's backend tests (`gl`, `system`) and the Slurm cluster test
#   scripts/test.sh PRESET  one preset's whole suite (release, asan, no-osmesa, debug), as before
# Each suite prints its wall time and its test counts when it ends, and the stage its total.
set -euo pipefail
cd "$(dirname "$0")/.."

stage_start=$SECONDS
summaries=()

# suite NAME PRESET [ctest arguments...]: builds PRESET (only the targets in $build_targets when
# it is set), runs its tests with the arguments.
build_targets=""
suite() {
  local name=$1 preset=$2
  shift 2
  local start=$SECONDS log
  log=$(mktemp)
  echo "== $name: build $preset${build_targets:+ ($build_targets)}"
  # shellcheck disable=SC2086  # the targets are words
  bash scripts/build.sh "$preset" $build_targets
  local built=$((SECONDS - start))
  echo "== $name: ctest --preset $preset $*"
  local status=0
  ctest --preset "$preset" -j "$(nproc)" "$@" 2>&1 | tee "$log" || status=$?
  local counts
  counts=$(grep -E '^[0-9]+% tests passed' "$log" | tail -n 1 || true)
  rm -f "$log"
  local line
  line=$(printf '%-28s %5d s (build %d s, tests %d s)  %s' "$name" $((SECONDS - start)) \
    "$built" $((SECONDS - start - built)) "${counts:-no tests ran}")
  summaries+=("$line")
  echo "== $line"
  if [ "$status" -ne 0 ]; then
    finish 1
  fi
}

finish() {
  echo "== summary (wall time, tests)"
  for line in "${summaries[@]}"; do echo "   $line"; done
  echo "== stage ${stage:-?}: $((SECONDS - stage_start)) s in all$([ "$1" -eq 0 ] || echo ', FAILED')"
  exit "$1"
}

readme_stage() {
  suite "release, all but cluster" release -LE '^cluster$'
  # Only what the sanitizer suite runs: not the system tests' executable nor the programs.
  build_targets="unit_tests gl_tests"
  suite "asan, unit and gl" asan -L '^(unit|gl)$' -LE '^slow$'
  build_targets=""
}

# Every argument checked before anything is installed, built or run.
case "${1:-}" in
  "" | quick | ci)
    [ $# -le 1 ] || { echo "test.sh: '$1' takes no further arguments (got '$2')" >&2; exit 2; } ;;
  *)
    for preset in "$@"; do
      case "$preset" in
        release | asan | no-osmesa | debug) ;;
        *) echo "test.sh: unknown stage or preset '$preset'; expected quick, ci or presets" \
             "(release, asan, no-osmesa, debug)" >&2
           exit 2 ;;
      esac
    done ;;
esac

bash scripts/setup.sh
case "${1:-}" in
  quick)
    stage=quick
    # The programs and the unit tests' executables: the gl and system ones wait for the next stage.
    build_targets="occsim occtune unit_tests"
    suite "release, unit" release -L '^unit$' -LE '^slow$'
    ;;
  "")
    stage=test
    readme_stage
    ;;
  ci)
    stage=ci
    readme_stage
    suite "no-osmesa, gl and system" no-osmesa -L '^(gl|system)$' -LE '^slow$'
    # The cluster test installs slurm-wlm and munge itself when missing (as root).
    suite "release, cluster" release -L '^cluster$'
    ;;
  release | asan | no-osmesa | debug)
    stage="presets $*"
    for preset in "$@"; do suite "$preset, all" "$preset"; done
    ;;
esac
finish 0
