#!/usr/bin/env bash
# Peak resident memory of `poundbench spectrum` over a case set of POINTS points (one family of
# 10 gaps x POINTS/10 log-spaced Pi2 (POINTS from 20 to 1e6), Moreau-Jean at 8 steps a period, 2 threads, --out a file),
# and of a one-point set, the process's own floor (its libraries). Issue 36: a million points
# (the format's cap) must stay under 200 MB; docs/cli.md quotes the measurement.
#   scripts/sweep_memory.sh [BUILD_DIR] [POINTS]    (default: build, 1000000)
# Prints "points peak_rss_mb wall_s" for both sets (GNU time's maximum resident set size).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
points=${2:-1000000}
pb=$(realpath "$build/poundbench")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

set_of() {  # set_of FILE PI3 PI2 (TOML values)
  cat > "$1" <<TOML
name = "memory"
[[family]]
name = "memory"
scene = "wall"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = $2
pi2 = $3
TOML
}
measure() {  # measure FILE POINTS
  /usr/bin/time -f "%M %e" -o "$work/time" "$pb" spectrum "$1" --solver moreau-jean --steps 8 --threads 2 \
    --out "$work/out.csv" 2> /dev/null
  read -r kb wall < "$work/time"
  echo "$2 $((kb / 1024)) $wall"
}
per_gap=$(( points / 10 ))
set_of "$work/one.toml" 0.5 1
set_of "$work/many.toml" '{ from = 0.1, to = 1, points = 10, spacing = "linear" }' \
  "{ from = 0.2, to = 5, points = $per_gap, spacing = \"log\" }"
echo "points peak_rss_mb wall_s"
measure "$work/one.toml" 1
measure "$work/many.toml" $(( 10 * per_gap ))
