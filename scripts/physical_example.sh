#!/usr/bin/env bash
# README's physical example (issue 35): an engineer's question asked in metres and seconds,
# two buildings (periods 0.5 s and 1 s, a 1 cm gap, eps 0.6) under Borrego Mountain 1942 at El Centro (cases/
# records/real/B-ELC000.AT2), answered by two `poundbench run` commands: the exact reference,
# and Moreau-Jean at a step in seconds. Writes reports/physical-example.json (the commands and
# their --json output), from which `reports/make_report.py --blocks-only` writes README's
# block `physical`. Seconds of one core.
#   scripts/physical_example.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build}/poundbench
case_args="--scene pair --pulse record --record cases/records/real/B-ELC000.AT2 --t0 0.5 --t1 1 --gap 0.01 --eps 0.6"
commands=("poundbench run $case_args --json"
          "poundbench run $case_args --solver moreau-jean --steps 64 --json")
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
{
  echo '{"commands": ['
  printf '  "%s",\n' "${commands[0]}"
  printf '  "%s"\n' "${commands[1]}"
  echo '], "results": ['
  # shellcheck disable=SC2086 # the words of the case are meant to split
  "$exe" ${commands[0]#poundbench } | sed 's/$/,/'
  # shellcheck disable=SC2086
  "$exe" ${commands[1]#poundbench }
  echo ']}'
} > "$tmp"
/usr/bin/python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$tmp"
mv "$tmp" reports/physical-example.json
trap - EXIT
echo "scripts/physical_example.sh: wrote reports/physical-example.json"
