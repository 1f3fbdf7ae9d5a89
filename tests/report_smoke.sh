#!/usr/bin/env bash
# The report script on a tiny sweep: every figure it should draw exists afterwards, and the
# README blocks it writes from its result files pass `make_report.py --check`.
#   report_smoke.sh POUNDBENCH BENCH SOURCE_DIR
set -euo pipefail
pb=$1 bench=$2 src=$3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$pb" spectrum "$src/cases/sets/smoke.toml" --out "$out/smoke.csv"
"$pb" workprecision "$src/cases/sets/smoke.toml" --settings "$src/cases/settings/smoke.toml" \
  --out "$out/wp.csv" --points "$out/points.csv"
"$pb" stress "$src/cases/sets/smoke.toml" --settings "$src/cases/settings/stress-smoke.toml" \
  --out "$out/stability.csv" --points "$out/stability-points.csv"
"$bench" --benchmark_filter='BM_Solve|BM_SweepFig4|BM_PaperSetThreadScaling' --benchmark_min_time=0.001 \
  --benchmark_out="$out/bench.json" --benchmark_out_format=json > /dev/null
# The compliant study where its solver is built (SUNDIALS), on the smoke set's wall families.
compliant=()
if "$pb" solvers | grep -q '^compliant '; then
  "$pb" workprecision "$src/cases/sets/smoke.toml" --settings "$src/cases/settings/compliant-smoke.toml" \
    --repetitions 1 --out "$out/compliant.csv" --points "$out/compliant-points.csv"
  compliant=(--compliant "$out/compliant.csv" --compliant-points "$out/compliant-points.csv")
fi
/usr/bin/python3 "$src/reports/provenance.py" --build-dir "$(dirname "$pb")" > "$out/provenance.json"
cp "$src/README.md" "$out/README.md"
/usr/bin/python3 "$src/reports/make_report.py" "$out/smoke.csv" --workprecision "$out/wp.csv" \
  --points "$out/points.csv" --bench "$out/bench.json" --provenance "$out/provenance.json" \
  --stress "$out/stability.csv" --stress-points "$out/stability-points.csv" "${compliant[@]}" --out "$out/report" \
  --readme "$out/README.md" > /dev/null
if [ ${#compliant[@]} -gt 0 ]; then
  for ext in png svg; do
    [ -s "$out/report/figures/compliant.$ext" ] || { echo "missing figure compliant.$ext"; exit 1; }
  done
  grep -q '| kelvin-voigt | cvode |' "$out/README.md" || { echo "README's compliant block has no Kelvin-Voigt row"; exit 1; }
fi
families=$(tail -n +2 "$out/smoke.csv" | cut -d, -f1 | sort -u)
missing=0
for f in $families; do
  for fig in "spectrum-$f" "wp-$f" "wp-spectra-$f"; do
    exts="png svg"
    [ "$fig" = "wp-$f" ] && exts=png  # the work-precision diagrams have no SVG (reports/wp.py)
    for ext in $exts; do
      [ -s "$out/report/figures/$fig.$ext" ] || { echo "missing figure $fig.$ext"; missing=1; }
    done
    grep -q "figures/$fig.png" "$out/report/README.md" || { echo "README.md does not show $fig"; missing=1; }
  done
done
for fig in stability-large-steps stability-verdicts; do
  for ext in png svg; do
    [ -s "$out/report/figures/$fig.$ext" ] || { echo "missing figure $fig.$ext"; missing=1; }
  done
  grep -q "figures/$fig.png" "$out/report/README.md" || { echo "README.md does not show $fig"; missing=1; }
done
# The engine past its stability limit fails `finite`; the stepper passes it at every step.
grep -q '^\* `ode dantzig-faithful`: \*\*finite fails\*\* at w_max h = .*10' "$out/report/README.md" ||
  { echo "stability summary does not show the diverging engine"; missing=1; }
grep -q '^\* `moreau-jean theta=0.5`: finite passes everywhere' "$out/report/README.md" ||
  { echo "stability summary does not show the stepper passing"; missing=1; }
# README's blocks: written from the report's result files, and they pass the check.
grep -q "^| sweep on 2 threads against 1" "$out/README.md" ||
  { echo "no thread speedup in README"; missing=1; }
grep -q "^| pair | 0.1 | " "$out/README.md" || { echo "no answer for the pair scene in README"; missing=1; }
/usr/bin/python3 "$src/reports/make_report.py" --check --readme "$out/README.md" --out "$out/report" > /dev/null ||
  { echo "README's blocks as written fail the check"; missing=1; }
exit $missing
