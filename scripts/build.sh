#!/usr/bin/env bash
# Configures and builds DriftLab. Usage: scripts/build.sh [BUILD_DIR [extra cmake args...]]
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-$src/build}"
shift || true
# ccache (when installed) makes rebuilds and fresh clones on the same machine cheap; paths
# are hashed relative to the checkout so that clones in other folders share the cache.
launcher=()
if command -v ccache >/dev/null && [[ " $* " != *COMPILER_LAUNCHER* ]]; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$src}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" "$@" >&2
cmake --build "$dir" -j"$(nproc)" >&2
