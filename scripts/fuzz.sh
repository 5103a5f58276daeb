#!/usr/bin/env bash
# Fuzzes every reader of outside input with libFuzzer (clang, ASan + UBSan): scenarios, glTF,
# viewer scripts, regression baselines, the tuner's sample log, --sweep and --segments strings,
# --culling files (a plugin culler's options included), plugin option descriptors and Masked
# Occlusion Culling's recorded frames (.mocrec) (tests/fuzz/fuzz_inputs.h).
# Usage: scripts/fuzz.sh [seconds per target, default 60] [target...]
#   targets: scenario gltf view_script baseline sample_log sweep segments culling_file
#            plugin_descriptor mocrec
# Seeds: the regression inputs in tests/fuzz/regressions/<target>/ (each holds a valid-* seed),
# plus every scenario under scenarios/ (scenario), the bundled glTF models (gltf) and the
# committed baselines (baseline); mocrec starts from its small seed (every record type in 489
# bytes: the real frames exceed -max_len) and its hand-made inputs (resolutions past the replay's
# memory budget and at its edge among them). Findings land in out/fuzz/<target>/ as crash-*,
# leak-*, timeout-* files: fix the bug, then copy the file into tests/fuzz/regressions/<target>/
# so the normal suite replays it (test_fuzz_regressions).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
all_targets=(scenario gltf view_script baseline sample_log sweep segments culling_file plugin_descriptor
             mocrec)
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for target in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $target "* ]] ||
    { echo "fuzz: unknown target '$target'; expected one of: ${all_targets[*]}" >&2; exit 2; }
done

bash scripts/setup.sh
# clang and its libFuzzer runtime are needed here only.
need=()
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$' || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  echo "fuzz: installing ${need[*]}"
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

# shellcheck disable=SC2046  # one argument a target
bash scripts/build.sh fuzz $(printf 'fuzz_%s ' "${targets[@]}")

status=0
for target in "${targets[@]}"; do
  work="out/fuzz/$target"
  mkdir -p "$work/corpus"
  case "$target" in
    scenario) find scenarios -name '*.json' ! -name '*.baseline.json' -exec cp {} "$work/corpus/" \; ;;
    gltf) find scenarios/assets \( -name '*.gltf' -o -name '*.glb' \) -exec cp {} "$work/corpus/" \; ;;
    baseline) find scenarios -name '*.baseline.json' -exec cp {} "$work/corpus/" \; ;;
  esac
  cp tests/fuzz/regressions/"$target"/* "$work/corpus/" 2>/dev/null || true
  echo "== fuzz_$target for $seconds s (corpus: $work/corpus, findings: $work/)"
  if ! ASAN_OPTIONS=detect_leaks=1 "./build/fuzz/tests/fuzz/fuzz_$target" "$work/corpus" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -max_len=262144 \
      -artifact_prefix="$work/" -print_final_stats=1 2>"$work/log.txt"; then
    status=1
    echo "fuzz_$target: FINDING, see $work/log.txt and the crash-/leak-/timeout- file in $work/"
  fi
  grep -E "^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb)" "$work/log.txt" || tail -3 "$work/log.txt"
done
exit $status
