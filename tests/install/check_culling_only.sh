#!/usr/bin/env bash
# OCCSIM_CULLING_ONLY=ON builds the culling library and its CPU test devices alone: GLM is all it
# finds, none of the simulator's dependencies (OSMesa, GLFW, CLI11, tinygltf, Ceres) is looked for.
# Usage: check_culling_only.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
work=$(mktemp -d /tmp/occsim-culling-only.XXXXXX)
trap 'rm -rf "$work"' EXIT
cmake -S "$source_dir" -B "$work/build" -DOCCSIM_CULLING_ONLY=ON -DCMAKE_BUILD_TYPE=Release \
  >"$work/configure.log"
# A package that was looked for leaves its <name>_DIR (CMake config) or pkgcfg_lib_ (pkg-config)
# entry in the cache.
looked_for='^(Ceres|CLI11|TinyGLTF|nlohmann_json|GTest|benchmark|glfw3)_DIR|^pkgcfg_lib_|^EGL_INCLUDE_DIR|^STB_INCLUDE_DIR'
if grep -qE "$looked_for" "$work/build/CMakeCache.txt"; then
  echo "check_culling_only: the culling-only build looked for a simulator dependency:" >&2
  grep -E "$looked_for" "$work/build/CMakeCache.txt" | head -5 >&2
  exit 1
fi
cmake --build "$work/build" -j 2 >/dev/null
cmake --install "$work/build" --prefix "$work/prefix" >/dev/null
[ -f "$work/prefix/lib/liboccsim_culling.a" ] && [ -f "$work/prefix/lib/liboccsim_culling_testing.a" ] \
  && [ ! -e "$work/prefix/bin/occsim" ] || { echo "check_culling_only: wrong install" >&2; exit 1; }
echo "check_culling_only: the culling library builds and installs alone"
