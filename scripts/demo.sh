#!/usr/bin/env bash
# The main job on the embedded default: build the two programs (not the tests and
# benchmarks), record a session from the simulated rig into driftlab.sqlite in the user's data
# directory, fit the seed-000 model to it, then open the GUI on it (or, with no display, render
# the main window to a PNG and say where).
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$src/build"
say() { echo "demo: $*" >&2; }

say "configuring $build (the first run takes a minute)"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
say "building driftlab and driftlab-cli only (the first build takes several minutes on 2 cores; tests and benchmarks are built by scripts/test.sh)"
set +o pipefail
cmake --build "$build" --target driftlab driftlab-cli -j"$(nproc)" 2>&1 |
  grep --line-buffered -E '^\[ *[0-9]+%\] (Linking|Built target)|error|warning' >&2
status=${PIPESTATUS[0]}
set -o pipefail
[ "$status" -eq 0 ] || { say "build failed (run cmake --build $build for the details)"; exit 1; }

data="${XDG_DATA_HOME:-$HOME/.local/share}/DriftLab"
mkdir -p "$data"
db="$data/driftlab.sqlite"
cli="$build/app/driftlab-cli"
gui="$build/app/driftlab"

# Seed-000 Table 2 programme (warm-up 84 min, cool-down 42 min, warm-up 42 min at 6000 mm/min)
# on the simulated rig, accelerated; then identify the seed-000 model on it.
say "recording 2:48:00 of the simulated rig into $db"
id=$("$cli" record --sim --duration 2:48:00 --out "$db" | sed -n 's/^session \([0-9][0-9]*\) .*/\1/p')
[ -n "$id" ] || { say "recording failed"; exit 1; }
say "fitting the seed-000 model to session $id"
"$cli" fit "$id" --model fdm --db "$db"
echo "session $id recorded and fitted in $db"

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  say "opening the GUI"
  exec "$gui" --db "$db" --show-session "$id"
else
  png="$data/driftlab-main-window.png"
  export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
  QT_QPA_PLATFORM=offscreen "$gui" --db "$db" --show-session "$id" --screenshot "$png"
  echo "no display: main window rendered to $png"
fi
