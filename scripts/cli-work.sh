# Sourced by the scripts that drive a built driftlab-cli (closed-loop-eval.sh, soak.sh), with
# the script's name as argument and $src set: cli is DRIFTLAB_CLI or the build's (exit 2 naming
# the script when it is not there); work is a private directory, removed on exit after the
# script's background jobs are killed.
cli="${DRIFTLAB_CLI:-$src/build/app/driftlab-cli}"
[ -x "$cli" ] || { echo "$1: no $cli (build first: scripts/build.sh)" >&2; exit 2; }
work="$(mktemp -d)"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
