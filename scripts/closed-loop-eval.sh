#!/usr/bin/env bash
# Closed-loop evaluation of live compensation on the simulated rig (issue 16, docs/export.md):
# a model fitted on one recording (training seed) drives `driftlab-cli compensate`, which writes
# its offsets over Modbus TCP to the simulated CNC of a second, held-out recording (test seed);
# the CNC applies them (a live compensation table: support points every ~100 mm, interpolated
# at the axis position) and the laser interferometer measures what is left. The same held-out
# recording without compensation is the reference. Reports, per model, the maximum and RMS
# positional thermal error of the interferometer runs (each run minus the cold reference run,
# `iso230` drift) and the improvement in percent.
#   scripts/closed-loop-eval.sh [SPEED [DURATION [TRAIN_SEED [TEST_SEED]]]]
#   defaults: 120x, 2:48:00 (seed 000 Table 2 programme), seeds 11 and 12
# Models: fdm (seed-000 screw model, `fit --json`) and synthetic (seed 002 eq. 26 on the screw
# PT100s, `fit --model synthetic --target interferometer`). Rig: seed002-instruments (baseline
# physics, screw-surface PT100s). RESULT_JSON=FILE also writes the figures as JSON;
# MIN_FDM_IMPROVEMENT=PCT exits 1 when the fdm model lowers the maximum error by less (CI).
# Needs a build (build/app/driftlab-cli, or DRIFTLAB_CLI) and python3.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
speed="${1:-120}"
duration="${2:-2:48:00}"
train_seed="${3:-11}"
test_seed="${4:-12}"
. "$src/scripts/cli-work.sh" closed-loop-eval
seconds=$(python3 -c "
d='$duration'.split(':'); print(int(d[0])*3600+int(d[1])*60+int(d[2]) if len(d)==3 else int(float(d[0])))")
wall=$(python3 -c "print(int($seconds/$speed)+1)")
port_base=$(( 20000 + (RANDOM % 20000) ))

# The rig with the CNC's compensation server and its register map (six support points).
python3 - "$src/resources/rigs/seed002-instruments.json" "$work" "$port_base" <<'PY'
import json, sys
rig = json.load(open(sys.argv[1])); work = sys.argv[2]; port = int(sys.argv[3])
lo, hi = rig.get('machine', {}).get('travel_mm', [0, 520])
n = 6
table = {"axes": [{"axis": "X", "address": 5700 + 2 * i, "position_mm": lo + (hi - lo) * i / (n - 1)} for i in range(n)],
         "resolution_um": 1}
json.dump(table, open(f"{work}/table-map.json", "w"), indent=1)
for k, name in enumerate(["none", "fdm", "synthetic"]):
    r = dict(rig)
    r["compensation_server"] = {"enabled": True, "host": "127.0.0.1", "port": port + k, "map": table}
    json.dump(r, open(f"{work}/rig-{name}.json", "w"), indent=1)
PY

echo "training: seed $train_seed, $duration, fitted fdm and synthetic" >&2
"$cli" record --rig seed002-instruments --seed "$train_seed" --duration "$duration" --out "$work/train.sqlite" 2>/dev/null >/dev/null
"$cli" fit 1 --db "$work/train.sqlite" --json "$work/fdm.json" >"$work/fit-fdm.log" 2>&1
"$cli" fit 1 --db "$work/train.sqlite" --model synthetic --target interferometer --out "$work/synthetic.json" >"$work/fit-syn.log" 2>&1

echo "held out: seed $test_seed at ${speed}x (${wall} s wall each, three recordings at once)" >&2
k=0
for name in none fdm synthetic; do
    "$cli" record --rig "$work/rig-$name.json" --seed "$test_seed" --duration "$duration" --speed "$speed" \
        --out "$work/test-$name.sqlite" >"$work/record-$name.log" 2>&1 &
    echo $! >"$work/record-$name.pid"
    if [ "$name" != none ]; then
        # Start following as soon as the session exists.
        for _ in $(seq 100); do "$cli" info --db "$work/test-$name.sqlite" >/dev/null 2>&1 && break; sleep 0.1; done
        "$cli" compensate "$work/$name.json" --db "$work/test-$name.sqlite" --session 1 --modbus "127.0.0.1:$((port_base + k))" \
            --map "$work/table-map.json" --enable --max-offset 100 --max-rate 20 --duration $((wall + 3)) \
            --json "$work/compensate-$name.json" >"$work/compensate-$name.log" 2>&1 &
    fi
    k=$((k + 1))
done
wait

python3 - "$cli" "$work" "$speed" "$duration" "$train_seed" "$test_seed" <<'PY'
import json, math, subprocess, sys, os
cli, work, speed, duration, train, test = sys.argv[1:7]
def drift(name):
    out = subprocess.run([cli, "iso230", "1", "--db", f"{work}/test-{name}.sqlite", "--json", "-"],
                         capture_output=True, text=True, check=True).stdout
    d = json.loads(out)["drift"]
    v = [p["drift_um"] for s in d["series"] for p in s["points"] if p["run"] != d["reference_run"] and p["drift_um"] is not None]
    return max(abs(x) for x in v), math.sqrt(sum(x * x for x in v) / len(v)), len(v)
rows = {}
base = drift("none")
rows["none"] = {"max_um": base[0], "rms_um": base[1], "points": base[2]}
for name in ["fdm", "synthetic"]:
    m, r, n = drift(name)
    c = json.load(open(f"{work}/compensate-{name}.json"))
    rows[name] = {"max_um": m, "rms_um": r, "points": n, "max_improvement_pct": 100 * (1 - m / base[0]),
                  "rms_improvement_pct": 100 * (1 - r / base[1]), "writes": c.get("writes"), "reconnects": c.get("reconnects"),
                  "period_jitter_ms": 1000 * (c.get("period_jitter_s") or 0)}
print(f"closed loop on held-out seed {test} ({duration} at {speed}x), models fitted on seed {train}")
print("| model | max error um | RMS um | max improvement | RMS improvement | writes |")
print("|---|---|---|---|---|---|")
for name, r in rows.items():
    if name == "none":
        print(f"| no compensation | {r['max_um']:.2f} | {r['rms_um']:.2f} | - | - | - |")
    else:
        print(f"| {name} | {r['max_um']:.2f} | {r['rms_um']:.2f} | {r['max_improvement_pct']:.1f} % | {r['rms_improvement_pct']:.1f} % | {r['writes']} |")
minimum = float(os.environ.get("MIN_FDM_IMPROVEMENT", "0") or 0)
if os.environ.get("RESULT_JSON"):
    json.dump({"speed": float(speed), "duration": duration, "train_seed": int(train), "test_seed": int(test), "results": rows},
              open(os.environ["RESULT_JSON"], "w"), indent=1)
if rows["fdm"]["max_improvement_pct"] < minimum:
    print(f"closed-loop-eval: FAILED: fdm lowers the maximum error by {rows['fdm']['max_improvement_pct']:.1f} %, "
          f"less than {minimum:.0f} %", file=sys.stderr)
    sys.exit(1)
PY
