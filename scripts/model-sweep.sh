#!/bin/sh
# Leave-runs-out sweep of the data-driven families (issue 32 item 7, docs/datadriven.md):
# builds the sweep databases and runs build/bench/bench_modelsweep on each.
#   1. FL_THERMAL cut into its 6 spindle cycles (scripts/fl-thermal-cycles.py), ch1..ch5;
#   2. rig campaign A: the three-group PT100 rig of tests/app/tst_datadriven, 6 sessions whose
#      ambient (17-25 degC), feed (3000-9000 mm/min) and seed differ;
#   3. rig campaign B (never tuned on): the same rig with a drifting ambient and a different
#      programme (custom phases), 6 sessions.
# Skips FL_THERMAL when ../shared/extdata is absent (DRIFTLAB_SHARED_DIR overrides).
#
#   scripts/model-sweep.sh [BUILD_DIR] [WORK_DIR]
set -eu
BUILD=${1:-build}
WORK=${2:-/tmp/driftlab-model-sweep}
HERE=$(cd "$(dirname "$0")/.." && pwd)
SHARED=${DRIFTLAB_SHARED_DIR:-$HERE/../shared}
CLI=$BUILD/app/driftlab-cli
BENCH=$BUILD/bench/bench_modelsweep
mkdir -p "$WORK"

FL=$SHARED/extdata/fl_thermal/fl_thermal_data.csv
if [ -f "$FL" ]; then
    if [ ! -f "$WORK/fl.sqlite" ]; then
        "$HERE/scripts/fl-thermal-cycles.py" "$FL" "$WORK/fl" >&2
        for n in 1 2 3 4 5 6; do
            "$CLI" import "$WORK/fl/cycle$n.bundle" --db "$WORK/fl.sqlite" >&2
        done
    fi
    echo "== FL_THERMAL, 6 spindle cycles as runs"
    for ch in ch1 ch2 ch3 ch4 ch5; do
        "$BENCH" "$WORK/fl.sqlite" $ch 1 2 3 4 5 6
    done
    if [ ! -f "$WORK/fl-whole.sqlite" ]; then
        "$HERE/scripts/fl-thermal-bundle.py" "$FL" "$WORK/fl-whole.bundle" >&2
        "$CLI" import "$WORK/fl-whole.bundle" --db "$WORK/fl-whole.sqlite" >&2
    fi
    echo "== FL_THERMAL anchor: time-ordered split, train 0-60 %, test 60-80 % (0-27.78 h, 27.78-37.05 h)"
    for ch in ch1 ch2 ch3 ch4 ch5; do
        "$BENCH" "$WORK/fl-whole.sqlite" $ch 1 --train-range 0:27.785 --holdout-range 27.785:37.047
    done
else
    echo "== FL_THERMAL skipped: $FL not found" >&2
fi

# The three-group rig (tests/app/tst_datadriven): ambient, motor and nut-housing PT100s.
rig() { # NAME AMBIENT_C DRIFT_K PROGRAMME_JSON
    cat > "$WORK/$1.json" <<JSON
{"format": "driftlab-rig", "version": 1, "name": "$1",
 "thermal": {"nut_housing": {"to_screw_W_K": 0.5},
             "ambient": {"mean_C": $2, "drift_amplitude_K": $3}},
 "programme": $4,
 "sensors": {"pt100": [
   {"id": "A1", "location": "ambient", "noise_K": 0.02}, {"id": "A2", "location": "ambient", "noise_K": 0.08},
   {"id": "A3", "location": "ambient", "noise_K": 0.18}, {"id": "M1", "location": "motor", "noise_K": 0.02},
   {"id": "M2", "location": "motor", "noise_K": 0.08}, {"id": "M3", "location": "motor", "noise_K": 0.18},
   {"id": "N1", "location": "nut", "noise_K": 0.02}, {"id": "N2", "location": "nut", "noise_K": 0.08},
   {"id": "N3", "location": "nut", "noise_K": 0.18}],
  "infrared": {"enabled": false}, "interferometer": {"enabled": false}}}
JSON
}
campaign() { # DB then lines "NAME AMBIENT DRIFT SEED PROGRAMME"
    db=$1
    shift
    if [ -f "$db" ]; then return; fi
    while read -r name ambient drift seed programme; do
        [ -n "$name" ] || continue
        rig "$name" "$ambient" "$drift" "$programme"
        "$CLI" record --rig "$WORK/$name.json" --seed "$seed" --duration 4:00:00 --out "$db" >&2
    done
}
preset() { echo "{\"preset\": \"seed000-table2\", \"feed_mm_min\": $1}"; }
campaign "$WORK/rigA.sqlite" <<EOF_A
a1 20 0.3 1 $(preset 6000)
a2 23 0.3 2 $(preset 3000)
a3 17 0.3 3 $(preset 9000)
a4 21 0.3 4 $(preset 4500)
a5 25 0.3 5 $(preset 7500)
a6 19 0.3 6 $(preset 6000)
EOF_A
echo "== rig campaign A (6 sessions, ambient 17-25 degC, feeds 3000-9000 mm/min)"
"$BENCH" "$WORK/rigA.sqlite" S1 1 2 3 4 5 6

phases() { # FEED1 FEED2: 1 h at FEED1, 1 h rest, 1 h at FEED2, 1 h rest
    echo "{\"phases\": [{\"name\": \"run1\", \"duration_s\": 3600, \"feed_mm_min\": $1}, {\"name\": \"rest1\", \"duration_s\": 3600, \"feed_mm_min\": 0}, {\"name\": \"run2\", \"duration_s\": 3600, \"feed_mm_min\": $2}, {\"name\": \"rest2\", \"duration_s\": 3600, \"feed_mm_min\": 0}]}"
}
campaign "$WORK/rigB.sqlite" <<EOF_B
b1 18 1.5 11 $(phases 4000 8000)
b2 22 1.0 12 $(phases 8000 2000)
b3 26 2.0 13 $(phases 6000 6000)
b4 20 1.5 14 $(phases 3000 9000)
b5 24 0.5 15 $(phases 9000 5000)
b6 16 1.0 16 $(phases 5000 7000)
EOF_B
echo "== rig campaign B (never tuned on; drifting ambient 16-26 degC, two feed blocks per session)"
"$BENCH" "$WORK/rigB.sqlite" S1 1 2 3 4 5 6
