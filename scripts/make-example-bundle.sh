#!/usr/bin/env bash
# Regenerates resources/bundles/example.bundle, the small example recording bundle that
# `driftlab-cli new-bundle` writes and the docs use: 1.5 h of the simulated baseline rig
# (seed-000 Table 2 warm-up at 6000 mm/min, then standstill), every channel thinned to one
# row per 10 s, infrared frames every 30 min, all three interferometer runs.
# Usage: scripts/make-example-bundle.sh [BUILD_DIR]
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$src/build}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$build/app/driftlab-cli" record --sim --duration 1:30:00 --seed 1 --out "$tmp/x.sqlite" --export "$tmp/full.bundle" >/dev/null
out="$src/resources/bundles/example.bundle"
rm -rf "$out"
python3 - "$tmp/full.bundle" "$out" <<'PY'
import csv, json, os, shutil, sys
src, out = sys.argv[1], sys.argv[2]
os.makedirs(os.path.join(out, "ir"))
m = json.load(open(os.path.join(src, "manifest.json")))
m.pop("simulated_rig", None)
m["machine"].pop("simulated_rig", None)
m["machine"]["name"] = "three-axis drilling centre (simulated)"
m["session"] = {"name": "Example: X-axis warm-up and cool-down (simulated)",
                "started": "2026-11-20T08:00:00Z", "operator": "DriftLab example",
                "notes": "1.5 h of DriftLab's simulated baseline rig, thinned to one row per 10 s"}
rows = list(csv.reader(open(os.path.join(src, "channels.csv"))))
header, keep, last, seen = rows[0], [rows[0]], {}, set()
for r in rows[1:]:
    t = float(r[0])
    for i, v in enumerate(r[1:], 1):
        if v != "":
            last[i] = format(float(v), ".6g")
    k = round(t / 10.0)
    if abs(t / 10.0 - k) < 1e-6 and k not in seen:
        seen.add(k)
        keep.append([str(10 * k)] + [last.get(i, "") for i in range(1, len(header))])
csv.writer(open(os.path.join(out, "channels.csv"), "w", newline=""), lineterminator="\n").writerows(keep)
frames = [r for r in csv.reader(open(os.path.join(src, "ir/index.csv")))][1:]
with open(os.path.join(out, "ir/index.csv"), "w") as f:
    f.write("time_s,file\n")
    for t, name in frames:
        if float(t) % 1800 == 0:
            shutil.copy(os.path.join(src, name), os.path.join(out, name))
            f.write(f"{t},{name}\n")
for name in ("interferometer.csv", "events.csv"):
    shutil.copy(os.path.join(src, name), os.path.join(out, name))
json.dump(m, open(os.path.join(out, "manifest.json"), "w"), indent=2)
open(os.path.join(out, "manifest.json"), "a").write("\n")
PY
du -sh "$out"
