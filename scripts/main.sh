#!/usr/bin/env bash
# The main job: set up, build, run the case sets through every solver, benchmark, report;
# then the paper report (scripts/paper.sh, reports/paper/).
#   scripts/main.sh          the default study (a few minutes on 2 cores, build included)
#   scripts/main.sh --full   the same study on 4x denser spectra (longer)
set -euo pipefail
cd "$(dirname "$0")/.."

study=cases/sets/workprecision.toml
[ "${1:-}" = "--full" ] && study=cases/sets/workprecision-full.toml

scripts/setup.sh --build-dir build --build-type Release
mkdir -p results
pb=build/poundbench

echo "main: the paper case set through the reference"
$pb spectrum cases/sets/paper.toml --solver event-driven --out results/paper-event-driven.csv
echo "main: the paper case set through the in-house stepper at its default N"
$pb spectrum cases/sets/paper.toml --solver moreau-jean --out results/paper-moreau-jean.csv

echo "main: work-precision study ($study)"
$pb workprecision "$study" --settings cases/settings/default.toml \
  --out results/workprecision.csv --points results/workprecision-points.csv

echo "main: stability on the stress case set"
$pb stress cases/sets/stress.toml --settings cases/settings/stress.toml \
  --out results/stability.csv --points results/stability-points.csv

echo "main: benchmarks"
build/bench/poundbench_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_min_time=0.05 --benchmark_out=results/bench.json --benchmark_out_format=json > /dev/null

/usr/bin/python3 reports/make_report.py results/paper-*.csv --workprecision results/workprecision.csv \
  --points results/workprecision-points.csv --bench results/bench.json \
  --stress results/stability.csv --stress-points results/stability-points.csv --out reports
cp results/workprecision.csv results/stability.csv reports/

echo "main: the paper report (reports/paper/)"
scripts/paper.sh
