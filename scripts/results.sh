#!/usr/bin/env bash
# The tables of docs/results.md: every scene of a set benchmarked with every algorithm, error
# measured, twice (two separate runs, so that the run-to-run spread can stand beside the means).
# Each run's console header gives the load average before and after it; run this on a quiet
# machine (no build, test or other benchmark beside it): a run on a busy one says so and is not a
# result. About 5 minutes per scene and run on a 2-core machine with --frames 100.
# Usage: scripts/results.sh [default|paper|general|levels|all] [--quick] [occsim bench options...]
#   The sets are those of scripts/scene_sets.sh (paper when none is named).
#   --quick: one run a scene of QUICK_FRAMES frames (below; --frames among the options wins), so
#   that each set ends within 10 minutes on the 2-core machine: a check that the table's command
#   works and a first look, not a result (no spread). Output under out/results-quick/.
#   With --algos among the options, each run is one process of those cullers alone (e.g.
#   `scripts/results.sh all --algos vfc,masked --sweep masked:drawn_occluders=false,true`, the
#   masked tables of docs/results.md); without, every registered culler as below.
# Output: out/results/<set>/<scene>/run-<n>/{summary.json,frames.csv,report.md} (with --algos:
# out/results-own-algos/...), then each set's
# table (scripts/results_table.py: means, spreads, the fastest conservative culler, loads), and
# how long the set took.
# `conditional` runs in a process of its own, beside VFC (run-<n>/conditional/): on llvmpipe its
# GL_QUERY_NO_WAIT draws make the driver flush a scene per batch of queries, and the scenes it
# leaves slow whatever renders after it in the same GL context (docs/conditional.md); its column
# is its speedup over the VFC of its own process.
set -euo pipefail
cd "$(dirname "$0")/.."
set_name=${1:-paper}
shift || true
source scripts/scene_sets.sh
set_list=$(scene_sets_of "$set_name" results.sh) || exit 2
mapfile -t sets <<<"$set_list"
# --quick is this script's; the rest goes to occsim bench.
QUICK_FRAMES=40
quick=false
own_algos=false
frames_given=false
bench_args=()
for arg in "$@"; do
  case "$arg" in
    --quick) quick=true; continue ;;
    --algos | --algos=*) own_algos=true ;;
    --frames | --frames=*) frames_given=true ;;
  esac
  bench_args+=("$arg")
done
runs=(1 2)
if $quick; then
  runs=(1)
  $frames_given || bench_args+=(--frames "$QUICK_FRAMES")
fi
bash scripts/setup.sh
bash scripts/build.sh release occsim
source scripts/core_dumps.sh  # a crash leaves a core (and says where)
source scripts/cullers_apart.sh  # $cullers_together; conditional runs apart (see above)
command -v python3 >/dev/null || { echo "results.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
results=out/results
$own_algos && results=out/results-own-algos
$quick && results=$results-quick
for set in "${sets[@]}"; do
  set_start=$SECONDS
  while read -r scene; do
    name=$(basename "$scene" .json)
    for run in "${runs[@]}"; do
      echo "== $scene, run $run ($(uptime))"
      if $own_algos; then
        ./build/release/sim/occsim bench "$scene" --error --out "$results/$set/$name/run-$run" \
          "${bench_args[@]}"
        continue
      fi
      ./build/release/sim/occsim bench "$scene" --error --algos "$cullers_together" \
        --out "$results/$set/$name/run-$run" "${bench_args[@]}"
      ./build/release/sim/occsim bench "$scene" --error --algos "vfc,$cullers_apart" \
        --out "$results/$set/$name/run-$run/$cullers_apart" "${bench_args[@]}"
    done
  done < <(scenes_of "$set")
  # The table of this set (docs/results.md's format): means of the runs, their spread, loads.
  if $quick; then
    python3 scripts/results_table.py --one-run "$results/$set"
  else
    python3 scripts/results_table.py "$results/$set"
  fi
  echo "== set $set: $((SECONDS - set_start)) s ($(uptime))"
done
