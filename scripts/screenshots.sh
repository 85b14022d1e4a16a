#!/usr/bin/env bash
# Regenerates docs/screenshots/<size>-<dock>.png: every dock of the main window at 1366x768
# and 1920x1080 (Xvfb), on two sessions of the simulated baseline rig (4 h seed 11, 3 h seed 12).
# Usage: scripts/screenshots.sh [BUILD_DIR]
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$src/build}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export XDG_CONFIG_HOME="$tmp/config" XDG_DATA_HOME="$tmp/data" XDG_RUNTIME_DIR="$tmp/run"
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
db="$tmp/screens.sqlite"
"$build/app/driftlab-cli" record --rig baseline --duration 4:00:00 --seed 11 --out "$db" --name "X axis, 4 h warm-up (seed 11)" >/dev/null 2>&1
"$build/app/driftlab-cli" record --rig baseline --duration 3:00:00 --seed 12 --out "$db" --name "X axis, 3 h warm-up (seed 12)" >/dev/null 2>&1
out="$src/docs/screenshots"
for size in 1366x768 1920x1080; do
  shot() { # NAME ARGS...
    local name="$1"; shift
    xvfb-run -a -s "-screen 0 ${size}x24" "$build/app/driftlab" --db "$db" "$@" --screenshot "$out/$size-$name.png" 2>&1 | grep screenshot
  }
  shot sessions --show-session 1 --view error-3d
  shot acquisition --show-session 2 --dock acquisition
  shot models --fit 1:2
  shot diagnosis --diagnose 1:2
  shot analysis --analysis 1:S1:2
done
