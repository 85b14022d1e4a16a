#!/usr/bin/env bash
# Builds DriftLab twice (normal, and with AddressSanitizer + UBSan) and runs every test.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
chmod 700 "$XDG_RUNTIME_DIR"
jobs="$(nproc)"

"$src/scripts/build.sh" "$src/build" -DDRIFTLAB_WERROR=ON
ctest --test-dir "$src/build" --output-on-failure -j"$jobs"
# A fast subset of the long runs recorded in docs/reliability.md: 3 hours of recording with
# failing instruments and a reader (the 24-hour run: scripts/soak.sh 24 240).
DRIFTLAB_CLI="$src/build/app/driftlab-cli" "$src/scripts/soak.sh" 3 600
# Live compensation closed on the simulated rig, held-out seed, the warm-up phase at 120x
# (docs/export.md records the full programme on five seeds, 90-91 %, goal 85 %): a regression
# guard at 80 %, with room for a loaded machine (the loop runs in wall time; CI runs here gave
# 88.4 %).
DRIFTLAB_CLI="$src/build/app/driftlab-cli" MIN_FDM_IMPROVEMENT=80 "$src/scripts/closed-loop-eval.sh" 120 1:24:00

# The sanitizer pass runs every test but the long diagnosis sweep subset (label
# "diagnosis", also tst_facesagree, which runs one), whose engine is covered under the
# sanitizers by tst_diagnosisengine,
# and tst_streamingcli (label "rss": it measures peak memory, which ASan inflates).
"$src/scripts/build.sh" "$src/build-asan" -DDRIFTLAB_SANITIZE=ON -DDRIFTLAB_WERROR=ON -DDRIFTLAB_BENCH=OFF
ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" \
LSAN_OPTIONS="suppressions=$src/scripts/lsan.supp:print_suppressions=0" \
UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
  ctest --test-dir "$src/build-asan" --output-on-failure -j"$jobs" -LE "diagnosis|rss"

# libFuzzer on every parser of user files, under ASan + UBSan (clang; a separate build):
# regression inputs first, then each harness for DRIFTLAB_FUZZ_SECONDS (docs/reliability.md).
DRIFTLAB_FUZZ_SEED="${DRIFTLAB_FUZZ_SEED:-1}" "$src/scripts/fuzz.sh" "${DRIFTLAB_FUZZ_SECONDS:-30}"
