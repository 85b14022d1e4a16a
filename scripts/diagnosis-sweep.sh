#!/bin/sh
# Full sweep of the mismatch diagnosis on concealed rig data (issues 7 and 18): SEEDS seeds per
# case (default 5) for "none", the eight candidate effects and four pairs of simultaneous
# effects (DRIFTLAB_DIAG_NO_PAIRS=1 leaves the pairs out), each a randomised machine with a
# training (4 h) and a validation (3 h) session recorded by the simulated rig, diagnosed blind
# by `driftlab-cli diagnose`. Prints the confusion matrix, the false-discovery rate on "none"
# and the held-out improvement; the raw outcomes go to OUT (default diagnosis-sweep.csv).
#
# usage: scripts/diagnosis-sweep.sh BUILD_DIR [SEEDS] [OUT]
set -eu
BUILD=${1:?usage: diagnosis-sweep.sh BUILD_DIR [SEEDS] [OUT]}
SEEDS=${2:-5}
OUT=${3:-diagnosis-sweep.csv}
TEST="$BUILD/tests/app/tst_diagnosis"
[ -x "$TEST" ] || { echo "diagnosis-sweep: $TEST not built (cmake --build $BUILD --target tst_diagnosis)" >&2; exit 2; }
QTEST_FUNCTION_TIMEOUT=${QTEST_FUNCTION_TIMEOUT:-100000000} DRIFTLAB_DIAG_SEEDS=$SEEDS DRIFTLAB_DIAG_FIRST_SEED=${FIRST_SEED:-1} DRIFTLAB_DIAG_NO_ASSERT=1 DRIFTLAB_DIAG_OUT="$OUT" \
    "$TEST" concealedEffects >&2 || true
python3 - "$OUT" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
def same(a, b):
    return sorted(a.split("+")) == sorted(b.split("+"))
pairs = [r for r in rows if "+" in r["truth"]]
rows = [r for r in rows if "+" not in r["truth"]]
effects = ["none", "motor_heat_fixed_end", "free_end_bearing_heat", "nonlinear_feed_heat", "heat_path_lag",
           "holding_heat", "structure_offset", "structure_linear", "screw_coolant"]
answers = effects + sorted({r["answer"] for r in rows} - set(effects))
short = {e: e[:10] for e in answers}
print("truth \\ answer".ljust(24) + "".join(short[a].rjust(11) for a in answers) + "   correct")
for t in effects:
    rs = [r for r in rows if r["truth"] == t]
    if not rs:
        continue
    counts = [sum(1 for r in rs if r["answer"] == a) for a in answers]
    print(t.ljust(24) + "".join(str(c).rjust(11) for c in counts) + ("   %d/%d" % (counts[answers.index(t)], len(rs))))
n = len(rows)
ok = sum(1 for r in rows if same(r["truth"], r["answer"]))
none = [r for r in rows if r["truth"] == "none"]
fd = sum(1 for r in none if r["answer"] != "none")
print("accuracy %d/%d = %.0f %%" % (ok, n, 100.0 * ok / max(n, 1)))
print("false discoveries on none: %d/%d" % (fd, len(none)))
eff = [r for r in rows if r["truth"] != "none"]
if eff:
    imp = [1 - float(r["corrected_heldout_um"]) / float(r["baseline_heldout_um"]) for r in eff]
    right = [1 - float(r["corrected_heldout_um"]) / float(r["baseline_heldout_um"]) for r in eff if r["truth"] == r["answer"]]
    print("held-out RMS improvement over effect cases: mean %.0f %%, median %.0f %%" %
          (100 * sum(imp) / len(imp), 100 * sorted(imp)[len(imp) // 2]))
    if right:
        print("  where the effect was named: mean %.0f %%" % (100 * sum(right) / len(right)))
print("mean diagnose wall time %.1f s" % (sum(float(r["seconds"]) for r in rows) / max(n, 1)))
if pairs:
    print()
    print("pairs of simultaneous effects (answer: the accepted codes in order; right = both named, nothing else)")
    for t in sorted({r["truth"] for r in pairs}):
        rs = [r for r in pairs if r["truth"] == t]
        answers = {}
        for r in rs:
            answers[r["answer"]] = answers.get(r["answer"], 0) + 1
        ok = sum(1 for r in rs if same(r["answer"], t))
        gain = [1 - float(r["corrected_heldout_um"]) / float(r["baseline_heldout_um"]) for r in rs]
        print("%-42s %d/%d right; held-out gain mean %.0f %%; answers: %s" % (t, ok, len(rs), 100 * sum(gain) / len(gain),
              ", ".join("%s x%d" % (a, c) for a, c in sorted(answers.items(), key=lambda x: -x[1]))))
    print("pairs right: %d/%d; mean diagnose wall time %.1f s" % (sum(1 for r in pairs if same(r["answer"], r["truth"])), len(pairs),
          sum(float(r["seconds"]) for r in pairs) / len(pairs)))
PY
