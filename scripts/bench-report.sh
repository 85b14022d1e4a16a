#!/usr/bin/env bash
# Speed of `driftlab-cli report` on a 10-hour session and of `driftlab-cli batch` over 10
# recordings on all cores against one at a time (docs/benchmarks.md, "Reports and batch").
# Usage: scripts/bench-report.sh [BUILD_DIR]   (default: build)
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
cli="${1:-$src/build}/app/driftlab-cli"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export QT_QPA_PLATFORM=offscreen
now() { date +%s.%N; }

"$cli" record --rig seed002-instruments --duration 10:00:00 --out "$tmp/10h.sqlite" 2>/dev/null
"$cli" select-points 1 --target S1 --db "$tmp/10h.sqlite" >/dev/null 2>&1
"$cli" fit 1 --model mlr --target S1 --points auto --train-range 0:8 --holdout-range 8:10 \
    --out "$tmp/model.json" --db "$tmp/10h.sqlite" >/dev/null 2>&1
for format in pdf html; do
  for run in 1 2 3; do
    t0=$(now)
    "$cli" report 1 --db "$tmp/10h.sqlite" --out "$tmp/10h.$format" 2>/dev/null
    echo "report of a 10-hour session ($format, run $run): $(echo "$(now) - $t0" | bc) s, $(stat -c %s "$tmp/10h.$format") bytes"
  done
done

mkdir -p "$tmp/in"
for i in $(seq -w 1 10); do cp -r "$src/resources/bundles/example.bundle" "$tmp/in/r$i.bundle"; done
cat > "$tmp/job.json" <<JOB
{"bundle_folder": "in", "output": "out",
 "steps": [{"step": "import"}, {"step": "select-points", "target": "S1"},
           {"step": "fit", "model": "mlr", "target": "S1", "points": "auto"},
           {"step": "plot", "view": "error-surface"}, {"step": "report", "format": "pdf"}]}
JOB
for jobs in 1 2; do
  t0=$(now)
  "$cli" batch "$tmp/job.json" --jobs $jobs 2>/dev/null
  echo "batch of 10 recordings x 5 steps, --jobs $jobs: $(echo "$(now) - $t0" | bc) s"
done
