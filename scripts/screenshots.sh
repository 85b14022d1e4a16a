#!/usr/bin/env bash
# Regenerates docs/screenshots/<size>-<view>.png: the main window maximised under a window
# manager (Xvfb + openbox, as a user sees it) at 1366x768 and 1920x1080, on two sessions of the
# simulated baseline rig (4 h seed 11, 3 h seed 12) and the instrumented rig (2 h seed 13, ISO 230),
# plus the first start (no database yet).
# Needs xvfb and openbox (apt-get install xvfb openbox); without openbox the window is sized to
# the screen instead. PNGs are quantised when pngquant is there (keeps the repository small).
# Usage: scripts/screenshots.sh [BUILD_DIR]
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$src/build}"
tmp="$(mktemp -d)"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; rm -rf "$tmp"; }
trap cleanup EXIT
export XDG_CONFIG_HOME="$tmp/config" XDG_DATA_HOME="$tmp/data" XDG_RUNTIME_DIR="$tmp/run"
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
db="$tmp/screens.sqlite"
"$build/app/driftlab-cli" record --rig baseline --duration 4:00:00 --seed 11 --out "$db" --name "X axis, 4 h warm-up (seed 11)" >/dev/null 2>&1
"$build/app/driftlab-cli" record --rig baseline --duration 3:00:00 --seed 12 --out "$db" --name "X axis, 3 h warm-up (seed 12)" >/dev/null 2>&1
# Session 3: the instrumented rig (3 bidirectional cycles per interferometer run) for the ISO 230 view.
"$build/app/driftlab-cli" record --rig seed002-instruments --duration 2:00:00 --seed 13 --out "$db" --name "X axis, ISO 230-2 runs (seed 13)" >/dev/null 2>&1
out="$src/docs/screenshots"
display=77
for size in 1366x768 1920x1080; do
  Xvfb ":$display" -screen 0 "${size}x24" -nolisten tcp & pids+=($!)
  sleep 1
  if command -v openbox >/dev/null; then DISPLAY=":$display" openbox & pids+=($!); sleep 1; fi
  shot() { # NAME ARGS...
    local name="$1"; shift
    DISPLAY=":$display" "$build/app/driftlab" "$@" --screenshot "$out/$size-$name.png" 2>&1 | grep screenshot
    if command -v pngquant >/dev/null; then pngquant --force --skip-if-larger --output "$out/$size-$name.png" "$out/$size-$name.png" || true; fi
  }
  shot sessions --db "$db" --show-session 1 --view error-3d
  shot acquisition --db "$db" --show-session 2 --dock acquisition
  shot iso230 --db "$db" --show-session 3 --central-view iso230
  # The live recording view: a simulated recording into a copy, a high limit T_motor crosses.
  cp "$db" "$tmp/live-$size.sqlite"
  shot live --db "$tmp/live-$size.sqlite" --record baseline --live-limit T_motor:22
  shot overlay --db "$db" --show-session 1 --overlay 2
  # The same overlay on one position axis: the last interferometer run of each session.
  shot overlay-position --db "$db" --show-session 1 --overlay 2,3 --view error-position
  shot models --db "$db" --fit 1:2
  shot diagnosis --db "$db" --diagnose 1:2
  shot analysis --db "$db" --analysis 1:S1:2
  shot first-start # no database yet: the first start
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  pids=()
  display=$((display + 1))
done
