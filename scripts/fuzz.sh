#!/usr/bin/env bash
# Fuzzes every parser that reads a user's or a peer's file (tests/fuzz) with libFuzzer under
# AddressSanitizer + UBSan: builds the harnesses with clang in build-fuzz/, replays the
# regression inputs (tests/fuzz/regressions/HARNESS/), then runs each harness for SECONDS
# (default 60) from a seed corpus of our own valid files, as many at a time as there are cores.
#   scripts/fuzz.sh [SECONDS [HARNESS...]]     e.g. scripts/fuzz.sh 600 bundle_channels
# DRIFTLAB_FUZZ_SEED=N fixes libFuzzer's seed (CI does, so that a CI run explores the same
# inputs each time and a new finding comes from a longer local run, not from chance).
# Prints executions, edges covered and corpus size per harness. Exit 1 if a harness crashed,
# hung (10 s), exceeded 2 GB or failed a regression input: the input is in
# build-fuzz/fuzz-work/HARNESS/findings/; once fixed, add it to tests/fuzz/regressions/HARNESS/.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
shift || true
build="${DRIFTLAB_FUZZ_BUILD:-$src/build-fuzz}"
all=(bundle_manifest bundle_channels bundle_interferometer bundle_events bundle_irindex ir_frame
     rig_json column_map csv_import rtl mtconnect offset_map model_json batch_job)
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=("${all[@]}")

launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$src}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
CC=clang CXX=clang++ cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=OFF \
  -DDRIFTLAB_BENCH=OFF -DDRIFTLAB_FUZZ=ON "${launcher[@]}" >/dev/null
echo "fuzz: building the harnesses in $build" >&2
cmake --build "$build" --target driftlab_fuzzers -j"$(nproc)" >/dev/null

# Seeds: our own valid files of each format.
seeds() {
  local b="$src/resources/bundles/example.bundle"
  case "$1" in
    bundle_manifest) echo "$b/manifest.json" ;;
    bundle_channels) echo "$b/channels.csv" ;;
    bundle_interferometer) echo "$b/interferometer.csv" ;;
    bundle_events) echo "$b/events.csv" ;;
    bundle_irindex) echo "$b/ir/index.csv" ;;
    ir_frame) ls "$b"/ir/*.png ;;
    rig_json) ls "$src"/resources/rigs/*.json ;;
    column_map) ls "$src"/resources/maps/*.json "$src"/tests/fuzz/corpus/column_map/* ;;
    rtl) ls "$src"/tests/data/rtl/*.rtl ;;
    mtconnect) ls "$src"/tests/data/mtconnect/*.xml ;;
    *) ls "$src/tests/fuzz/corpus/$1"/* ;;
  esac
}

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=1"
cat "$src/scripts/lsan.supp" "$src/scripts/fuzz-lsan.supp" >"$build/lsan.supp"
export LSAN_OPTIONS="suppressions=$build/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

run_one() {
  local h="$1" exe="$build/tests/fuzz/fuzz_$1" work="$build/fuzz-work/$1"
  rm -rf "$work"
  mkdir -p "$work/seeds" "$work/corpus" "$work/findings"
  seeds "$h" | while read -r f; do cp "$f" "$work/seeds/"; done
  local reg="$src/tests/fuzz/regressions/$h"
  if [ -d "$reg" ] && [ -n "$(ls -A "$reg")" ]; then
    if ! "$exe" -timeout=10 -rss_limit_mb=2048 "$reg"/* >"$work/regressions.log" 2>&1; then
      echo "$h FAILED-REGRESSION see $work/regressions.log" >"$work/summary"
      return 0
    fi
  fi
  local status=ok
  local seed=()
  [ -z "${DRIFTLAB_FUZZ_SEED:-}" ] || seed=(-seed="$DRIFTLAB_FUZZ_SEED")
  "$exe" "${seed[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$work/findings/" "$work/corpus" "$work/seeds" >"$work/log" 2>&1 || status=FINDING
  local execs cov corp
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || echo 0)
  cov=$(grep -o 'cov: [0-9]*' "$work/log" | tail -1 | grep -o '[0-9]*' || echo 0)
  corp=$(ls "$work/corpus" | wc -l)
  echo "$h $status $execs $cov $corp" >"$work/summary"
}
export -f run_one seeds
export src build seconds

echo "fuzz: ${#harnesses[@]} harnesses, ${seconds} s each, $(nproc) at a time" >&2
printf '%s\n' "${harnesses[@]}" | xargs -P "$(nproc)" -I{} bash -c 'run_one "$@"' _ {}

failed=0
printf '%-22s %-8s %12s %8s %8s\n' harness result executions edges corpus
for h in "${harnesses[@]}"; do
  read -r name status execs cov corp <"$build/fuzz-work/$h/summary" || { echo "$h: no result"; failed=1; continue; }
  printf '%-22s %-8s %12s %8s %8s\n' "$name" "$status" "$execs" "$cov" "$corp"
  if [ "$status" != ok ]; then
    failed=1
    tail -40 "$build/fuzz-work/$h/log" >&2 || true
    ls "$build/fuzz-work/$h/findings" >&2 || true
  fi
done
exit "$failed"
