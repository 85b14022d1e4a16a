#!/usr/bin/env python3
"""Cuts the FL_THERMAL CSV into its spindle cycles, one recording bundle per cycle, as runs
for the leave-runs-out sweep (issue 32, scripts/model-sweep.sh). A cycle starts where the
spindle switches on from rest (the first also holds the idle minutes before it) and runs to
the next such switch: 6 cycles of 6-8 h (1250, 2500, 3750, 5000, 3500 rpm for 4 h on / 4 h off,
then the 500-4500 rpm steps). Each bundle's time restarts at 0; values are unchanged (the
probes are not re-zeroed: a cycle starts where the previous one left the machine). Channel ids
as scripts/fl-thermal-bundle.py (scripts/fl_thermal.py). Standard library only.

    scripts/fl-thermal-cycles.py ../shared/extdata/fl_thermal/fl_thermal_data.csv OUTDIR
"""
import csv
import datetime
import os
import sys

import fl_thermal


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: fl-thermal-cycles.py FL_THERMAL.csv OUTDIR")
    source, outdir = sys.argv[1], sys.argv[2]
    with open(source, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    header = rows[0]
    if header[0] != "time_s" or "spindle_rpm" not in header:
        sys.exit(f"{source}: line 1: expected time_s first and a spindle_rpm column")
    rpm = header.index("spindle_rpm")
    ids, channels = fl_thermal.channels(source, header)
    data = rows[1:]
    starts = [0]
    for k in range(1, len(data)):
        if float(data[k - 1][rpm]) == 0.0 and float(data[k][rpm]) > 0.0 and k > 60:
            starts.append(k)
    starts = sorted(set(starts))
    if len(starts) > 1 and starts[1] < 60:  # the idle minutes before the first switch-on
        starts.pop(1)
    os.makedirs(outdir, exist_ok=True)
    for n, begin in enumerate(starts, start=1):
        end = starts[n] if n < len(starts) else len(data)
        bundle = os.path.join(outdir, f"cycle{n}.bundle")
        os.makedirs(bundle, exist_ok=True)
        t0 = float(data[begin][0])
        with open(os.path.join(bundle, "channels.csv"), "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(ids)
            for row in data[begin:end]:
                w.writerow([f"{float(row[0]) - t0:g}"] + row[1:])
        hours = t0 / 3600.0
        started = datetime.datetime(2024, 5, 23, tzinfo=datetime.timezone.utc) + datetime.timedelta(seconds=t0)
        fl_thermal.write_manifest(bundle, {"name": f"FL_THERMAL cycle {n} (from {hours:.2f} h)",
                                           "started": started.strftime("%Y-%m-%dT%H:%M:%SZ")}, channels)
        print(f"{bundle}: {end - begin} samples from {hours:.2f} h")


if __name__ == "__main__":
    main()
