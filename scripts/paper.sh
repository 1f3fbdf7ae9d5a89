#!/usr/bin/env bash
# The paper report, reports/paper/: set up and build, run the paper's case sets through the
# reference, then write the page and its figures. Works from a clean clone.
#   scripts/paper.sh            set up and build first
#   scripts/paper.sh --built    build/ is up to date (scripts/main.sh has just built it)
set -euo pipefail
cd "$(dirname "$0")/.."

[ "${1:-}" = "--built" ] || scripts/setup.sh --build-dir build --build-type Release
mkdir -p results/paper
pb=build/poundbench

echo "paper: the paper case sets through the reference"
$pb spectrum cases/sets/paper.toml --solver event-driven --out results/paper/reference.csv
$pb spectrum cases/sets/paper-report.toml --solver event-driven --out results/paper/extra.csv
/usr/bin/python3 reports/paper/make_paper.py results/paper/reference.csv results/paper/extra.csv \
  --poundbench "$pb" --out reports/paper
