#!/usr/bin/env bash
# docs/tuning.md's results: statistical+ tuned per scene by occtune on every scene of a set, each
# tuning confirmed by occtune on the frames it fitted and on the held-out variant (the scenario's
# seed + 1), then the scene benchmarked with the tuned file beside every other culler (the fastest
# conservative peer in the same run). Every scene twice: two separate sessions (sampling seeds 1
# and 2), so the run-to-run spread stands beside the means. The load average before and after each
# step is logged; run this on a quiet machine (no build, test or other benchmark beside it).
# Usage: scripts/tune_table.sh [default|paper|general|levels|all] [occtune options...]
#   (the sets of scripts/scene_sets.sh)
#   e.g. scripts/tune_table.sh all --frames 120 --budget 17
# Output: out/tuning/<set>/<scene>/run-<n>/{tune/,peers/,load.txt}, then the tables
# (scripts/tune_table.py out/tuning/<set>). Rerun with the same flags to resume a stopped table:
# runs already benchmarked are kept, a tuning session whose fit failed is resumed.
set -euo pipefail
cd "$(dirname "$0")/.."
set_name=${1:-all}
shift || true
source scripts/scene_sets.sh  # the sets, spelled once
set_list=$(scene_sets_of "$set_name" tune_table.sh) || exit 2
mapfile -t sets <<<"$set_list"
# The occsim bench flags that match occtune's --frames, when given.
bench_flags=()
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  if [[ ${args[i]} == --frames ]]; then bench_flags+=(--frames "${args[i + 1]}"); fi
  if [[ ${args[i]} == --frames=* ]]; then bench_flags+=("${args[i]}"); fi
done
bash scripts/setup.sh
bash scripts/build.sh release occsim occtune
source scripts/core_dumps.sh  # a crash leaves a core (and says where)
# The peers: $cullers_together, every registered culler but conditional, which slows what renders
# after it in the same process on llvmpipe (scripts/cullers_apart.sh).
source scripts/cullers_apart.sh
for set in "${sets[@]}"; do
  for scene in $(scenes_of "$set"); do
    name=$(basename "$scene" .json)
    for run in 1 2; do
      out="out/tuning/$set/$name/run-$run"
      # A table stopped part-way resumes: a run whose peers were benchmarked is kept as it is.
      if [[ -f "$out/peers/summary.json" ]]; then
        echo "== $scene, run $run: kept from before ($out)"
        continue
      fi
      rm -rf "$out/peers" "$out/failed.txt"
      mkdir -p "$out"
      echo "== $scene, run $run ($(uptime))"
      status=0
      if [[ -f "$out/tune/confirmation.json" && -f "$out/load.txt" ]] &&
        grep -q '^tune after:' "$out/load.txt"; then
        # The session finished before the table stopped (in the peers bench): keep it and its
        # loads, and bench the peers again.
        echo "tune_table.sh: $out/tune finished before; benchmarking the peers again"
        sed -i '/^peers /d' "$out/load.txt"
      else
        echo "tune before: $(cut -d' ' -f1-3 /proc/loadavg)" > "$out/load.txt"
        # Exit 3 (the confirmation rejected the values) is a result, not a failure of the script.
        ./build/release/tune/occtune "$scene" --algo statistical+ --seed "$run" --out "$out/tune" \
          "$@" || status=$?
        # A fit that did not converge (exit 1, the samples all logged): the same session resumed
        # with ten times Ceres' iterations refits the logged samples without measuring them again.
        if [[ $status -ne 0 && ! -f "$out/tune/confirmation.json" && -f "$out/tune/samples.jsonl" ]]
        then
          echo "tune_table.sh: occtune exit $status on $scene; resuming with --max-fit-iterations 2000"
          status=0
          ./build/release/tune/occtune "$scene" --algo statistical+ --seed "$run" --out "$out/tune" \
            "$@" --resume --max-fit-iterations 2000 || status=$?
        fi
        echo "tune after: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/load.txt"
      fi
      if [[ $status -ne 0 && ! -f "$out/tune/confirmation.json" ]]; then
        # Said in the table (tune_table.py lists the run as failed), and the other scenes go on.
        echo "tune_table.sh: occtune failed on $scene, run $run (exit $status)" | tee "$out/failed.txt" >&2
        continue
      fi
      culling=()
      [[ -f "$out/tune/tuned.json" ]] && culling=(--culling "$out/tune/tuned.json")
      echo "peers before: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/load.txt"
      status=0
      ./build/release/sim/occsim bench "$scene" --error --algos "$cullers_together" "${culling[@]}" \
        "${bench_flags[@]}" --out "$out/peers" || status=$?
      echo "peers after: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/load.txt"
      if [[ $status -ne 0 ]]; then
        # A crash keeps its core (core_dumps.sh) and says so; the table goes on, and a rerun with
        # the same flags benches these peers again.
        echo "tune_table.sh: the peers bench failed on $scene, run $run (exit $status)" |
          tee "$out/failed.txt" >&2
        rm -rf "$out/peers"
      fi
    done
  done
  python3 scripts/tune_table.py "out/tuning/$set"
done
