#!/usr/bin/env bash
# The main job on the embedded default: build, record a session from the simulated rig
# into driftlab.sqlite in the user's data directory, analyse it, then open the GUI on it
# (or, with no display, render the main window to a PNG and say where).
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$src/build"
"$src/scripts/build.sh" "$build"

data="${XDG_DATA_HOME:-$HOME/.local/share}/DriftLab"
mkdir -p "$data"
db="$data/driftlab.sqlite"
cli="$build/app/driftlab-cli"
gui="$build/app/driftlab"

"$cli" record --sim --duration 2:48:00 --out "$db"
"$cli" analyse --db "$db"
echo "session database: $db"

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec "$gui" --db "$db"
else
  png="$data/driftlab-main-window.png"
  export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
  QT_QPA_PLATFORM=offscreen "$gui" --db "$db" --screenshot "$png"
  echo "no display: main window rendered to $png"
fi
