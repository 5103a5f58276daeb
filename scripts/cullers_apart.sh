# Sourced by the table scripts (results.sh, tune_table.sh): which cullers share a process.
# `conditional` runs apart: on llvmpipe its GL_QUERY_NO_WAIT draws make the driver flush a scene
# per batch of queries, and what it leaves slows whatever renders after it in the same GL context
# (docs/conditional.md). Every run now gives it a GL context of its own, which keeps that out of
# the others' timings (measured there); the tables keep it in a process of its own as well, so that
# they compare with the tables made before. Needs ./build/release/sim/occsim built.
# shellcheck shell=bash
cullers_apart=conditional
# Every registered culler but those apart, comma-separated (for --algos).
cullers_together=$(./build/release/sim/occsim cullers | grep -E '^[a-z0-9+-]+:' | cut -d: -f1 |
  grep -vx "$cullers_apart" | paste -sd,)
