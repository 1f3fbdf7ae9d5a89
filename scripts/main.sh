#!/usr/bin/env bash
# The main job: set up, build, run the paper case set through every solver, write the report.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh --build-dir build --build-type Release
mkdir -p results
for solver in event-driven; do
  echo "main: paper case set through $solver"
  build/poundbench spectrum cases/sets/paper.toml --solver "$solver" --out "results/paper-$solver.csv"
done
/usr/bin/python3 reports/make_report.py results/paper-*.csv --out reports
