#!/usr/bin/env python3
"""Turns the FL_THERMAL CSV (../shared/extdata/fl_thermal/fl_thermal_data.csv) into a recording
bundle with the agreed channel ids (t1..t16 degC temperatures, ch1..ch5 um displacements,
spindle_rpm with role spindle), for `driftlab-cli import` until `import-csv --map
resources/maps/fl_thermal.json` is available. Standard library only.

    scripts/fl-thermal-bundle.py ../shared/extdata/fl_thermal/fl_thermal_data.csv fl.bundle
"""
import csv
import json
import os
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: fl-thermal-bundle.py FL_THERMAL.csv OUT.bundle")
    source, bundle = sys.argv[1], sys.argv[2]
    with open(source, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    if header[0] != "time_s":
        sys.exit(f"{source}: line 1: expected time_s as the first column, got {header[0]!r}")
    channels, ids = [], ["time_s"]
    for name in header[1:]:
        if name.endswith("_C"):
            cid, kind, unit, role = name[:-2], "temperature", "degC", ""
        elif name.endswith("_um"):
            cid, kind, unit, role = name[:-3], "displacement", "um", ""
        elif name == "spindle_rpm":
            cid, kind, unit, role = name, "other", "rpm", "spindle"
        else:
            sys.exit(f"{source}: line 1: unknown column {name!r}")
        ids.append(cid)
        channels.append({"id": cid, "kind": kind, "sensor": "unknown", "unit": unit, "role": role})
    os.makedirs(bundle, exist_ok=True)
    with open(os.path.join(bundle, "channels.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(ids)
        for number, row in enumerate(rows[1:], start=2):
            if not row:
                continue
            if len(row) != len(header):
                sys.exit(f"{source}: line {number}: {len(row)} fields, expected {len(header)}")
            w.writerow(row)
    manifest = {"format": "thermal-error-bundle", "version": 1,
                "session": {"name": "FL_THERMAL 46 h spindle test", "started": "2024-05-23T00:00:00Z"},
                "machine": {"name": "CNC spindle (FL_THERMAL)"}, "channels": channels}
    with open(os.path.join(bundle, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1)
    print(f"{bundle}: {len(rows) - 1} samples of {len(channels)} channels")


if __name__ == "__main__":
    main()
