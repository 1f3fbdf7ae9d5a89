#!/usr/bin/env bash
# README's engineer's question (issues 35, 51), asked in metres and seconds: two buildings
# (periods 0.4 s and 0.9 s, 800 t and 1,600 t, a 2 cm gap, eps 0.65) under three records scaled
# to 0.35 g (examples/engineer/buildings.toml), answered by two commands: `spectrum` through the
# exact reference (per record: whether they pound, how hard, the peak with and without
# pounding, the gap that avoids pounding either way and the rules' gaps), and `workprecision`
# over the same file with cases/settings/physical.toml (every contact model, step in seconds
# and stiffness in N/m, its error against the reference and its cost). Writes
# reports/physical-example.json (the commands, the rows and the search's summary rows), from
# which `reports/make_report.py --blocks-only` writes README's block `physical`. Seconds of one core.
#   scripts/physical_example.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build}/poundbench
file=examples/engineer/buildings.toml
commands=("poundbench spectrum $file --out rows.csv"
          "poundbench workprecision $file --settings cases/settings/physical.toml --out search.csv")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$exe" spectrum "$file" --out "$tmp/rows.csv" 2> /dev/null
# One thread: the costs are CPU time per run either way, and the example shares the machine.
"$exe" workprecision "$file" --settings cases/settings/physical.toml --threads 1 --out "$tmp/search.csv" \
  --points "$tmp/points.csv" 2> /dev/null
/usr/bin/python3 - "$tmp" "${commands[@]}" <<'PY'
import csv, json, sys
folder, commands = sys.argv[1], sys.argv[2:]
def rows(name):
    with open(f"{folder}/{name}", newline="") as f:
        return [r for r in csv.DictReader(f) if r["family"]]  # the closing count line, if any, is not a row
with open(f"{folder}/example.json", "w") as f:
    # The exact Kelvin-Voigt solutions' rows (the compliant element's own reference, at each
    # stiffness of the list): the contact force a model of the pounding gives.
    forces = [{k: r[k] for k in ("point", "settings", "contact_force_max", "status")} for r in rows("points.csv")
              if r["solver"] == "event-driven" and '"kelvin-voigt"' in r["settings"]]
    json.dump({"commands": commands, "rows": rows("rows.csv"), "search": rows("search.csv"), "forces": forces},
              f, indent=1)
    f.write("\n")
PY
mv "$tmp/example.json" reports/physical-example.json
echo "scripts/physical_example.sh: wrote reports/physical-example.json"
