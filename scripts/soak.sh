#!/usr/bin/env bash
# A long recording with failing instruments and a reader browsing at the same time (issue 21,
# docs/reliability.md): records HOURS of simulated session time at SPEED x real time through
# the device threads, with the PT100 module, the probe and the CNC each dropping out
# periodically (fail_every_s) and coming back, while a second process lists, inspects and
# plots the growing session over and over. Checks and prints:
#   - the recorder's resident memory over the run (peak, and growth from the first tenth
#     of the run to the end) against BOUND_MB (default 300);
#   - 'database is locked' (or any other failure) in the reader: must be none;
#   - every outage is a gap in the session: a 'gap start' and 'gap end' event per outage,
#     no samples inside an outage window, no dropped blocks, and outside the outages each
#     channel's samples on its rate (nothing lost);
#   - PRAGMA integrity_check ok and the session complete.
#   scripts/soak.sh [HOURS [SPEED]]        default 24 h at 240x (6 minutes)
# Needs a build (build/app/driftlab-cli, or DRIFTLAB_CLI) and sqlite3, python3.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
hours="${1:-24}"
speed="${2:-240}"
bound_mb="${BOUND_MB:-300}"
. "$src/scripts/cli-work.sh" soak
duration=$(python3 -c "print(int(round($hours*3600)))")

# Outages in session seconds: PT100 module 120 s every 2 h, probe 90 s every 3 h, CNC 150 s
# every 5 h, each starting at its own offset (long enough to be seen at high speed: a device
# polled every 50 ms of wall time misses an outage shorter than that).
cat >"$work/rig.json" <<EOF
{"format": "driftlab-rig", "version": 1, "name": "soak rig", "machine": {"name": "soak", "axis": "X"},
 "devices": [
  {"id": "pt100", "type": "sim-pt100", "fail_at_s": 1800, "fail_for_s": 120, "fail_every_s": 7200},
  {"id": "probe", "type": "sim-probe", "fail_at_s": 2700, "fail_for_s": 90, "fail_every_s": 10800},
  {"id": "cnc", "type": "sim-cnc", "fail_at_s": 4000, "fail_for_s": 150, "fail_every_s": 18000},
  {"id": "laser", "type": "sim-interferometer"},
  {"id": "camera", "type": "sim-infrared"}
 ]}
EOF
db="$work/soak.sqlite"
echo "soak: ${hours} h at ${speed}x (about $((duration / ${speed%.*})) s wall), database $db" >&2
"$cli" record --rig "$work/rig.json" --duration "$duration" --speed "$speed" --db "$db" \
  --json "$work/record.json" 2>"$work/record.log" &
rec=$!

# RSS of the recorder once a second.
(
  while kill -0 "$rec" 2>/dev/null; do
    awk '/VmRSS/ {print $2}' "/proc/$rec/status" 2>/dev/null || true
    sleep 1
  done
) >"$work/rss.txt" &

# The reader: list, info and a temperature plot of the session being recorded, in a loop.
reads=0 failures=0
until [ -f "$db" ]; do sleep 0.2; done
sleep 2
while kill -0 "$rec" 2>/dev/null; do
  for args in "list" "info" "plot 1 --view timeseries --out $work/t.png --force" "plot 1 --view error-time --out $work/e.png --force"; do
    # shellcheck disable=SC2086
    if ! "$cli" $args --db "$db" >/dev/null 2>"$work/reader.err"; then
      # Early in the run a view may have nothing to show yet: that is an answer, not a failure.
      if kill -0 "$rec" 2>/dev/null && ! grep -q "has no data for the view" "$work/reader.err"; then
        failures=$((failures + 1))
        echo "soak: reader failed: $args: $(head -c 300 "$work/reader.err")" >&2
      fi
    fi
    reads=$((reads + 1))
  done
done
set +e
wait "$rec"
code=$?
set -e
sleep 1
locked=$(grep -c "database is locked" "$work/record.log" || true)

CLI="$cli" python3 - "$db" "$work/rss.txt" "$work/record.json" "$duration" "$bound_mb" "$reads" "$failures" "$code" "$locked" <<'EOF'
import json, sqlite3, sys
db, rssf, recf, duration, bound, reads, failures, code, locked = sys.argv[1:]
duration = float(duration); bound = float(bound)
ok = True
def check(cond, what):
    global ok
    print(("ok    " if cond else "FAIL  ") + what)
    ok &= bool(cond)
rss = [int(x) / 1024 for x in open(rssf).read().split()]
check(int(code) == 0, f"recorder exit code {code}")
if rss:
    first = max(rss[: max(1, len(rss) // 10)])
    peak = max(rss)
    check(peak < bound, f"recorder resident memory: peak {peak:.0f} MB (bound {bound:.0f} MB), "
                        f"{first:.0f} MB in the first tenth of the run, growth {peak - first:.0f} MB")
check(int(failures) == 0 and int(locked) == 0,
      f"reader: {reads} reads while recording, {failures} failed, 'database is locked' {locked} times")
rec = json.load(open(recf))
con = sqlite3.connect(db)
check(con.execute("pragma integrity_check").fetchone()[0] == "ok", "PRAGMA integrity_check")
check(con.execute("select complete from sessions where id = 1").fetchone()[0] == 1, "session complete")
devices = {d["id"]: d for d in rec.get("devices", [])}
check(all(d["dropped_blocks"] == 0 for d in devices.values()),
      "dropped blocks: " + ", ".join(f"{k} {d['dropped_blocks']}" for k, d in devices.items()))
outages = {"pt100": (1800, 120, 7200), "probe": (2700, 90, 10800), "cnc": (4000, 150, 18000)}
events = [(t, label) for t, label in con.execute("select t, label from events where session_id = 1 order by t")]
for dev, (at, length, every) in outages.items():
    windows = []
    t = at
    while t < duration - 1:
        windows.append((t, t + length))
        t += every
    starts = [t for t, l in events if l.startswith(f"gap start: {dev} ")]
    ends = [t for t, l in events if l.startswith(f"gap end: {dev} ")]
    # An outage that ends after the recording has no 'gap end'.
    check(len(starts) == len(windows) and len(ends) == len([w for w in windows if w[1] < duration - 1]),
          f"{dev}: {len(windows)} outages, {len(starts)} gap starts, {len(ends)} gap ends, "
          f"{devices.get(dev, {}).get('reconnects', '?')} reconnects")
# Per channel, from an export of the session: every declared gap of a device is a hole in
# each of its channels, starting at the last sample before it; every other hole (a spacing
# over 1.5 times the median) is one of the PT100 sensor dropouts the rig simulates (bursts
# of at most dropout_max_samples = 20 samples). Nothing else is missing.
import csv, subprocess, os
bundle = os.path.join(os.path.dirname(db), "soak.bundle")
subprocess.run([os.environ["CLI"], "export", "1", bundle, "--db", db], check=True, stderr=subprocess.DEVNULL)
with open(os.path.join(bundle, "channels.csv"), newline="") as f:
    rows = csv.reader(f)
    header = next(rows)
    times = {k: [] for k in header[1:]}
    for r in rows:
        t = float(r[0])
        for k, cell in zip(header[1:], r[1:]):
            if cell != "":
                times[k].append(t)
device_of = lambda key: "pt100" if key.startswith("T") else "probe" if key.startswith("S") else "cnc" if key in ("X", "F") else None
gap_starts = {dev: [t for t, l in events if l.startswith(f"gap start: {dev} ")] for dev in outages}
total = 0
for key, ts in times.items():
    dev = device_of(key)
    if dev is None or len(ts) < 3:
        continue
    total += len(ts)
    d = sorted(b - a for a, b in zip(ts, ts[1:]))
    step = d[len(d) // 2]
    holes = [(a, b) for a, b in zip(ts, ts[1:]) if b - a > 1.5 * step]
    is_gap = lambda h: any(abs(s - h[0]) <= 2 * step for s in gap_starts[dev])
    gaps = [h for h in holes if is_gap(h)]
    dropouts = [h for h in holes if not is_gap(h)]
    longest = max([(b - a) / step - 1 for a, b in dropouts], default=0)
    in_gaps = sum(b - a - step for a, b in gaps) / step
    check(len(gaps) == len(gap_starts[dev]) and longest <= 20.5 and (dev == "pt100" or not dropouts),
          f"{key} ({dev}, every {step:g} s): {len(ts)} samples; {len(gaps)} holes at the {len(gap_starts[dev])} declared gaps "
          f"({in_gaps:.0f} samples' worth); {len(dropouts)} sensor dropouts of at most {longest:.0f} samples")
print(f"soak: {total} samples checked")
print("soak:", "passed" if ok else "FAILED")
sys.exit(0 if ok else 1)
EOF
