#!/usr/bin/env bash
# Installs exactly the Debian 12 packages occsim needs that are missing, and nothing when all are
# present. Needs root (or sudo) only when something must be installed.
# `setup.sh cluster` installs instead what the cluster test needs (tests/cluster/slurm_regress.sh:
# a single-node Slurm with munge), which the README's build and test commands do not.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git          # toolchain
  ninja-build                                   # the presets' generator (builds in parallel across targets)
  ccache                                        # presets after the first recompile only what differs
  libegl-dev libopengl-dev                      # headless OpenGL through EGL (the default backend)
  libegl-mesa0                                  # Mesa's EGL driver: the llvmpipe software device
  libosmesa6-dev                                # headless OpenGL through OSMesa (optional backend)
  libglfw3-dev                                  # window (occsim view)
  libglm-dev nlohmann-json3-dev libcli11-dev libtinygltf-dev libstb-dev
  libsqlite3-dev                                # objects.sqlite (--record objects, occsim why)
  libmeshoptimizer-dev                          # simplified occluder meshes (masked)
  libceres-dev                                  # the tuner
  libgtest-dev libgmock-dev libbenchmark-dev    # tests and micro-benchmarks
  xvfb xauth                                    # window test under a virtual X server
  gnuplot-nox                                   # charts (occsim bench --plots)
  clang-format                                  # the format check (scripts/format.sh)
  python3                                       # scripts/make_levels.py (its tests), the tables
)
if [ "${1:-}" = cluster ]; then
  packages=(slurm-wlm munge)
elif [ $# -gt 0 ]; then
  echo "setup: unknown argument '$1'; expected none or 'cluster'" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); else
    echo "setup: missing packages (${missing[*]}) and not root; run as root or install sudo" >&2
    exit 1
  fi
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
