#!/usr/bin/env bash
# README's physical example (issue 35): an engineer's question asked in metres and seconds,
# two buildings of 1000 t (periods 0.5 s and 1 s, a 1 cm gap, eps 0.6) under Borrego
# Mountain 1942 at El Centro (cases/records/real/B-ELC000.AT2), answered by two commands:
# the exact reference (`run --json`: the peak in metres, the impacts), and the search
# (`workprecision` over that one case with cases/settings/physical.toml: every model, step in
# seconds and stiffness in N/m, its error against the reference and its cost). Writes
# reports/physical-example.json (the commands, the reference's --json output and the search's
# summary rows), from which `reports/make_report.py --blocks-only` writes README's block
# `physical`. Seconds of one core.
#   scripts/physical_example.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build}/poundbench
case_args="--scene pair --pulse record --record cases/records/real/B-ELC000.AT2 --t0 0.5 --t1 1 --m0 1e6 --m1 1e6 --gap 0.01 --eps 0.6"
commands=("poundbench run $case_args --json"
          "poundbench workprecision --settings cases/settings/physical.toml $case_args")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck disable=SC2086 # the words of the case are meant to split
"$exe" ${commands[0]#poundbench } > "$tmp/reference.json"
# One thread: the costs are CPU time per run either way, and the example shares the machine.
# shellcheck disable=SC2086
"$exe" ${commands[1]#poundbench } --threads 1 > "$tmp/search.csv"
/usr/bin/python3 - "$tmp" "${commands[@]}" <<'PY'
import csv, json, sys
folder, commands = sys.argv[1], sys.argv[2:]
with open(f"{folder}/reference.json") as f:
    reference = json.load(f)
with open(f"{folder}/search.csv", newline="") as f:
    search = [r for r in csv.DictReader(f) if r["family"]]  # the closing count line, if any, is not a row
with open(f"{folder}/example.json", "w") as f:
    json.dump({"commands": commands, "reference": reference, "search": search}, f, indent=1)
    f.write("\n")
PY
mv "$tmp/example.json" reports/physical-example.json
echo "scripts/physical_example.sh: wrote reports/physical-example.json"
