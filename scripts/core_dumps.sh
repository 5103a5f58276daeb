# Sourced by the benchmark scripts (bench.sh, results.sh, ablation.sh, valgrind.sh): core dumps
# on, so that a crash in a long run leaves a core to read instead of two lines in the kernel log
# (issue 34's intermittent segfault left nothing else), and one line saying where it will go.
# The limit is raised to what the hard limit allows (unlimited unless an administrator capped
# it); kernel.core_pattern decides the place: a plain name is relative to the crashing process's
# folder (the repository root here: the scripts cd there), a leading | hands the core to a
# program (systemd-coredump: `coredumpctl list occsim`, `coredumpctl gdb`).
ulimit -c "$(ulimit -H -c)" 2>/dev/null || true
core_limit=$(ulimit -c)
core_pattern=$(cat /proc/sys/kernel/core_pattern 2>/dev/null || echo core)
case "$core_pattern" in
  '|'*) core_where="handed to ${core_pattern#|} (kernel.core_pattern)" ;;
  /*) core_where="$core_pattern (kernel.core_pattern)" ;;
  *) core_where="$PWD/$core_pattern (kernel.core_pattern: relative to the crashing process's folder)" ;;
esac
if [ "$core_limit" = 0 ]; then
  echo "core dumps: off (the hard limit, ulimit -H -c, is 0: a crash leaves no core)"
else
  echo "core dumps: on (ulimit -c $core_limit); a crash leaves its core at $core_where"
fi
