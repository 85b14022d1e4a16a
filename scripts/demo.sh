#!/usr/bin/env bash
# The main job on the embedded default: build the two programs (not the tests and
# benchmarks), record sessions from the simulated rig into driftlab.sqlite in the user's data
# directory (the seed-000 programme at three feeds), fit the seed-000 model to them, then open
# the GUI on the first (or, with no display, render the main window to a PNG and say where).
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

# Seed-000 Table 2 programme (warm-up 84 min, cool-down 42 min, warm-up 42 min) on the simulated
# rig, accelerated, at 6000, 3000 and 9000 mm/min as the paper identifies it: one feed cannot
# separate the feed laws from lambda and P_f. Then identify the seed-000 model on the three.
ids=()
seed=1
for feed in 6000 3000 9000; do
  say "recording 2:48:00 of the simulated rig at $feed mm/min into $db"
  sid=$("$cli" record --sim --feed "$feed" --seed "$seed" --duration 2:48:00 --out "$db" \
    --name "Simulated rig, seed-000 programme at $feed mm/min" |
    sed -n 's/^session \([0-9][0-9]*\) .*/\1/p')
  [ -n "$sid" ] || { say "recording failed"; exit 1; }
  ids+=("$sid")
  seed=$((seed + 1))
done
id=${ids[0]}
say "fitting the seed-000 model to sessions ${ids[*]}"
"$cli" fit "${ids[@]}" --model fdm --db "$db"
echo "sessions ${ids[*]} recorded and fitted in $db; the GUI shows session $id"

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  say "opening the GUI"
  exec "$gui" --db "$db" --show-session "$id"
else
  png="$data/driftlab-main-window.png"
  export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
  QT_QPA_PLATFORM=offscreen "$gui" --db "$db" --show-session "$id" --screenshot "$png"
  echo "no display: main window rendered to $png"
fi
