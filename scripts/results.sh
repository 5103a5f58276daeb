#!/usr/bin/env bash
# The tables of docs/results.md: every scene of a set benchmarked with every algorithm, error
# measured, twice (two separate runs, so that the run-to-run spread can stand beside the means).
# Each run's console header gives the load average before and after it; run this on a quiet
# machine (no build, test or other benchmark beside it): a run on a busy one says so and is not a
# result. About 5 minutes per scene and run on a 2-core machine with --frames 100.
# Usage: scripts/results.sh [paper|general|levels|default|all] [occsim bench options...]
#   With --algos among the options, each run is one process of those cullers alone (e.g.
#   `scripts/results.sh all --algos vfc,masked --sweep masked:drawn_occluders=false,true`, the
#   masked tables of docs/results.md); without, every registered culler as below.
#   paper:   scenarios/paper/{teapots,city,library,plant}.json (the default set)
#   general: scenarios/general/*.json (the generalisation set)
#   levels:  scenarios/levels/*.json (game levels: courtyards, interior, street canyon; generalisation)
#   default: scenarios/teapots.json
#   all:     default, paper, general and levels, one table each
# Output: out/results/<set>/<scene>/run-<n>/{summary.json,frames.csv,report.md} (with --algos:
# out/results-own-algos/...), then each set's
# table (scripts/results_table.py: means, spreads, the fastest conservative culler, loads).
# `conditional` runs in a process of its own, beside VFC (run-<n>/conditional/): on llvmpipe its
# GL_QUERY_NO_WAIT draws make the driver flush a scene per batch of queries, and the scenes it
# leaves slow whatever renders after it in the same GL context (docs/conditional.md); its column
# is its speedup over the VFC of its own process.
set -euo pipefail
cd "$(dirname "$0")/.."
set_name=${1:-paper}
shift || true
case "$set_name" in
  paper|general|levels|default) sets=("$set_name") ;;
  all) sets=(default paper general levels) ;;
  *) echo "results.sh: unknown set '$set_name'; expected paper, general, levels, default or all" >&2; exit 2 ;;
esac
scenes_of() {
  case "$1" in
    paper) echo scenarios/paper/teapots.json scenarios/paper/city.json scenarios/paper/library.json \
                scenarios/paper/plant.json ;;
    general) echo scenarios/general/*.json ;;
    levels) echo scenarios/levels/*.json ;;
    default) echo scenarios/teapots.json ;;
  esac
}
bash scripts/setup.sh
bash scripts/build.sh release occsim
source scripts/core_dumps.sh  # a crash leaves a core (and says where)
source scripts/cullers_apart.sh  # $cullers_together; conditional runs apart (see above)
command -v python3 >/dev/null || { echo "results.sh: the table needs python3 (apt-get install python3)" >&2; exit 1; }
own_algos=false
for arg in "$@"; do [[ $arg == --algos || $arg == --algos=* ]] && own_algos=true; done
results=out/results
$own_algos && results=out/results-own-algos
for set in "${sets[@]}"; do
  for scene in $(scenes_of "$set"); do
    name=$(basename "$scene" .json)
    for run in 1 2; do
      echo "== $scene, run $run ($(uptime))"
      if $own_algos; then
        ./build/release/sim/occsim bench "$scene" --error --out "$results/$set/$name/run-$run" "$@"
        continue
      fi
      ./build/release/sim/occsim bench "$scene" --error --algos "$cullers_together" \
        --out "$results/$set/$name/run-$run" "$@"
      ./build/release/sim/occsim bench "$scene" --error --algos "vfc,$cullers_apart" \
        --out "$results/$set/$name/run-$run/$cullers_apart" "$@"
    done
  done
  # The table of this set (docs/results.md's format): means of the two runs, their spread, loads.
  python3 scripts/results_table.py "$results/$set"
done
