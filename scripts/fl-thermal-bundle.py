#!/usr/bin/env python3
"""Turns the FL_THERMAL CSV (../shared/extdata/fl_thermal/fl_thermal_data.csv) into a recording
bundle with the agreed channel ids (scripts/fl_thermal.py), for `driftlab-cli import` until `import-csv --map
resources/maps/fl_thermal.json` is available. Standard library only.

    scripts/fl-thermal-bundle.py ../shared/extdata/fl_thermal/fl_thermal_data.csv fl.bundle
"""
import csv
import os
import sys

import fl_thermal


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: fl-thermal-bundle.py FL_THERMAL.csv OUT.bundle")
    source, bundle = sys.argv[1], sys.argv[2]
    with open(source, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    if header[0] != "time_s":
        sys.exit(f"{source}: line 1: expected time_s as the first column, got {header[0]!r}")
    ids, channels = fl_thermal.channels(source, header)
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
    fl_thermal.write_manifest(bundle, {"name": "FL_THERMAL 46 h spindle test", "started": "2024-05-23T00:00:00Z"}, channels)
    print(f"{bundle}: {len(rows) - 1} samples of {len(channels)} channels")


if __name__ == "__main__":
    main()
