#!/usr/bin/env bash
# Configures and builds DriftLab. Usage: scripts/build.sh [BUILD_DIR [extra cmake args...]]
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-$src/build}"
shift || true
cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >&2
cmake --build "$dir" -j"$(nproc)" >&2
