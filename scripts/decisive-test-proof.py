#!/usr/bin/env python3
"""Follow the diagnosis's "which test would decide" advice on the simulated rig (issue 36 item 5).

usage: scripts/decisive-test-proof.py BUILD_DIR OUT_DIR [--follow TEST]

--follow TEST follows that proposed test instead of the top-ranked one (a control: a test the
advice ranks low should not decide).

1. Makes a rig file from resources/rigs/baseline.json with holding heat (2 W at standstill) and a
   training programme with only two 3-minute pauses in 4 h, and a validation programme (3 h) with
   two 20-minute pauses; records both (`driftlab-cli record`, seeds 21 / 22).
2. Diagnoses them (`driftlab-cli diagnose`): the truth, holding heat, is hard to see in training.
3. Reads `decisive_test` from the JSON and records the training programme again on the same
   machine (seed 23) with the top-ranked added programme appended (cool-down, standstill phases,
   another feed) or the change it names (runs every 10 min, a surface PT100). The interferometer
   keeps the rig's 30-min runs throughout, so the only change is the advised programme.
4. Diagnoses the new training recording against the same validation recording and prints both
   answers beside the truth.
Only main's record command and the branch's diagnose are used; nothing here is tuned on the answer.
"""
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
build, out = sys.argv[1], sys.argv[2]
follow = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == "--follow" else None
cli = os.path.join(build, "app", "driftlab-cli")
os.makedirs(out, exist_ok=True)
db = os.path.join(out, "proof.sqlite")
if os.path.exists(db):
    sys.exit("decisive-test-proof: %s exists; give an empty OUT_DIR" % db)
base = json.load(open(os.path.join(ROOT, "resources", "rigs", "baseline.json")))
TRUTH = "holding_heat"


def rig(name, phases, extra=None):
    r = json.loads(json.dumps(base))
    r["name"] = name
    r["effects"]["holding_heat"] = {"enabled": True, "power_W": 2.0}
    r["programme"] = {"phases": [{"name": n, "duration_s": d, "feed_mm_min": f, "travel_mm": [0, 520]} for n, d, f in phases]}
    if extra:
        extra(r)
    path = os.path.join(out, name + ".json")
    json.dump(r, open(path, "w"), indent=1)
    return path, sum(d for _, d, _ in phases)


def hms(s):
    s = int(round(s))
    return "%d:%02d:%02d" % (s // 3600, s // 60 % 60, s % 60)


def record(path, duration, seed, name):
    subprocess.run([cli, "record", "--rig", path, "--duration", hms(duration), "--seed", str(seed), "--out", db, "--name", name],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def diagnose(train, validate, js):
    p = subprocess.run([cli, "diagnose", "--train", str(train), "--validate", str(validate), "--db", db, "--json", js],
                       stderr=subprocess.PIPE, text=True)
    sys.stderr.write("".join(l + "\n" for l in p.stderr.splitlines() if not l.startswith("[")))
    return json.load(open(js))


TRAIN = [("run1", 4500, 6000), ("pause1", 180, 0), ("run2", 4800, 4000), ("pause2", 180, 0), ("run3", 4740, 6000)]
VALID = [("run1", 3600, 5000), ("pause1", 1200, 0), ("run2", 3600, 3000), ("pause2", 1200, 0), ("run3", 1200, 6000)]
path, d = rig("train", TRAIN)
record(path, d, 21, "train")
path, d = rig("validate", VALID)
record(path, d, 22, "validate")
first = diagnose(1, 2, os.path.join(out, "first.json"))
advice = first.get("decisive_test", {})
print("first diagnosis: %s (truth %s), held-out RMS %.3f -> %.3f um" %
      (first["effect"], TRUTH, first["baseline"]["heldout_rms_um"], first["corrected"]["heldout_rms_um"]))
if not advice.get("given"):
    sys.exit("no advice given: nothing to follow")
top = advice["tests"][0] if not follow else next(t for t in advice["tests"] if t["test"] == follow)
print("advice (%s): %s" % (advice["trigger"], advice["summary"]))
for t in advice["tests"]:
    print("  %-22s chi2 %8.1f  max diff %6.2f %s  gain %3.0f %%" %
          (t["test"], t["expected_chi2"], t["max_difference"], t["unit"], 100 * t["expected_heldout_gain"]))

# Follow the top-ranked test (or the one asked for).
code, desc = top["test"], top["description"]
feed = [float(x) for x in re.findall(r"at (\d+) mm/min", desc)]
extra, phases = None, list(TRAIN)
if code == "cooldown":
    phases += [("advised cool-down", 3 * 3600, 0)]
elif code == "standstill_phases":
    phases += [("advised run", 2400, feed[0]), ("advised standstill", 2400, 0), ("advised run", 2400, feed[0]),
               ("advised standstill", 3600, 0)]
elif code in ("feed_high", "feed_low"):
    phases += [("advised feed", 3 * 3600, feed[0])]
elif code == "dense_runs":
    def extra(r):
        r["sensors"]["interferometer"]["interval_s"] = 600
elif code.startswith("screw_pt100_"):
    xi = {"fixed_end": 0.05, "middle": 0.5, "free_end": 0.95}[code[len("screw_pt100_"):]]

    def extra(r):
        r["sensors"]["pt100"].append({"id": "T_screw", "location": "screw_surface", "screw_position_m": xi * 0.8,
                                      "rate_Hz": 1, "noise_K": 0.02, "dropout_probability": 0, "dropout_max_samples": 1})
path, d = rig("train-advised", phases, extra)
record(path, d, 23, "train, advised")
second = diagnose(3, 2, os.path.join(out, "second.json"))
print("followed '%s': %s" % (code, desc))
print("second diagnosis: %s (truth %s), held-out RMS %.3f -> %.3f um" %
      (second["effect"], TRUTH, second["baseline"]["heldout_rms_um"], second["corrected"]["heldout_rms_um"]))
for c in second["candidates"][:2]:
    print("  %s: %s" % (c["effect"], "; ".join(c["evidence"][:2])))
print("RESULT: %s" % ("right" if second["effect"] == TRUTH else "not right"))
