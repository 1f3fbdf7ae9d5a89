#!/usr/bin/env bash
# The report script on a tiny sweep: every figure it should draw exists afterwards, and the
# README blocks it writes from its result files pass `make_report.py --check`; then
# `poundbench report` on a stress study and a spectrum, and on inputs it must refuse.
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
# (grep reads the whole list: with -q it would stop at the match, and poundbench, writing the
# rest, would die of SIGPIPE and fail the pipeline under pipefail, skipping this part unseen.)
compliant=()
if "$pb" solvers | grep '^compliant ' > /dev/null; then
  "$pb" workprecision "$src/cases/sets/smoke.toml" --settings "$src/cases/settings/compliant-smoke.toml" \
    --repetitions 1 --out "$out/compliant.csv" --points "$out/compliant-points.csv"
  compliant=(--compliant "$out/compliant.csv" --compliant-points "$out/compliant-points.csv")
fi
# The yielding section (reports/yielding.py) on the yielding set through the reference and
# Moreau-Jean (about 3 s each).
for s in event-driven moreau-jean; do
  "$pb" spectrum "$src/cases/sets/yielding.toml" --solver "$s" --out "$out/yielding-$s.csv"
done
# The time-steppers on yielding bodies (reports/yielding_wp.py: README's yielding block), about
# 2 s of CPU.
"$pb" workprecision "$src/cases/sets/workprecision-yielding.toml" --settings "$src/cases/settings/yielding.toml" \
  --repetitions 1 --out "$out/workprecision-yielding.csv" --points "$out/workprecision-yielding-points.csv"
/usr/bin/python3 "$src/reports/provenance.py" --build-dir "$(dirname "$pb")" > "$out/provenance.json"
cp "$src/README.md" "$out/README.md"
/usr/bin/python3 "$src/reports/make_report.py" "$out/smoke.csv" --workprecision "$out/wp.csv" \
  --points "$out/points.csv" --bench "$out/bench.json" --provenance "$out/provenance.json" \
  --stress "$out/stability.csv" --stress-points "$out/stability-points.csv" "${compliant[@]}" \
  --yielding "$out/yielding-event-driven.csv" "$out/yielding-moreau-jean.csv" \
  --yielding-wp "$out/workprecision-yielding.csv" --out "$out/report" \
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
  for ext in png svg; do
    [ -s "$out/report/figures/spectrum-$f.$ext" ] || { echo "missing figure spectrum-$f.$ext"; missing=1; }
  done
  grep -q "figures/spectrum-$f.png" "$out/report/README.md" || { echo "README.md does not show spectrum-$f"; missing=1; }
  # the work-precision diagrams and spectra: a figure per family and solver family (reports/wp.py)
  for fig in "wp-$f-in-house" "wp-spectra-$f-in-house"; do
    [ -s "$out/report/figures/$fig.png" ] || { echo "missing figure $fig.png"; missing=1; }
    grep -q "figures/$fig.png" "$out/report/README.md" || { echo "README.md does not show $fig"; missing=1; }
  done
done
for fig in yielding-yield-fig4 yielding-yield-fig5; do
  [ -s "$out/report/figures/$fig.png" ] || { echo "missing figure $fig.png"; missing=1; }
  grep -q "figures/$fig.png" "$out/report/README.md" || { echo "README.md does not show $fig"; missing=1; }
done
grep -q '^\* \*\*Self-similarity (master curves).\*\* .* within [0-9.]*e-1[0-9] of each other' "$out/report/README.md" ||
  { echo "the yielding section does not find its spectra self-similar to round-off"; missing=1; }
grep -q '^| moreau-jean theta=0.5 | ' "$out/report/README.md" || { echo "no Moreau-Jean row on yielding cases"; missing=1; }
grep -q '^  The elastic finding (body 0.s Pi1 is .*) \(survives\|does not survive\) yielding' "$out/report/README.md" ||
  { echo "the yielding section does not say whether Pi6's effect survives yielding"; missing=1; }
for scope in "wall yielding" "pair yielding"; do
  grep -q "^| $scope | 0.01 | " "$out/README.md" || { echo "README's yielding block has no $scope answer"; missing=1; }
  grep -q "^| $scope | 0.01 | " "$out/report/README.md" || { echo "the report has no $scope answer"; missing=1; }
done
grep -q '<script type="application/json" id="report-data">' "$out/report/report.html" ||
  { echo "no report.html with its data"; missing=1; }
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

# `poundbench report` on the other kinds of study (a work-precision study's: report_page_test.py):
# the stress study, and a spectrum's rows (two of the smoke set's families).
"$pb" report "$out/stability.csv" --points "$out/stability-points.csv" --out "$out/stress-report" > /dev/null
grep -q "figures/stability-verdicts.png" "$out/stress-report/README.md" || { echo "no stress verdicts"; missing=1; }
grep -q 'class="verdict fail"' "$out/stress-report/report.html" || { echo "no failed verdict in the page"; missing=1; }
awk -F, 'NR == 1 || $1 == "wall-sine" || $1 == "pair-touching"' "$out/smoke.csv" > "$out/two.csv"
"$pb" report "$out/two.csv" --out "$out/spectrum-report" > /dev/null
for f in wall-sine pair-touching; do
  [ -s "$out/spectrum-report/figures/spectrum-$f.png" ] || { echo "no spectrum of $f"; missing=1; }
done
# A file that is no study, and points of another study: exit 2, one line, nothing written.
refused() {  # refused CODE TEXT ARGS...: poundbench report ARGS exits CODE with one line holding TEXT
  local code=$1 text=$2 got rc=0
  shift 2
  got=$("$pb" report "$@" 2>&1 > /dev/null) || rc=$?
  [ "$rc" = "$code" ] || { echo "report $*: exit $rc, not $code"; missing=1; }
  [ "$(printf '%s\n' "$got" | wc -l)" = 1 ] && [[ "$got" == *"$text"* ]] ||
    { echo "report $*: not one line with '$text': $got"; missing=1; }
}
refused 2 "bench.json:1: header: not a poundbench result file" "$out/bench.json" --out "$out/none1"
refused 2 "not the points of this study" "$out/wp.csv" --points "$out/stability-points.csv" --out "$out/none2"
[ ! -e "$out/none1" ] && [ ! -e "$out/none2" ] || { echo "a refused report wrote its folder"; missing=1; }
# No matplotlib for the interpreter (a module that fails to import stands in), no interpreter: exit 1.
mkdir -p "$out/no-mpl/matplotlib"
echo 'raise ImportError("stand-in")' > "$out/no-mpl/matplotlib/__init__.py"
PYTHONPATH="$out/no-mpl" refused 1 "has no matplotlib (Debian: python3-matplotlib" "$out/wp.csv" --out "$out/none3"
POUNDBENCH_PYTHON=/nonexistent/python3 refused 1 "POUNDBENCH_PYTHON=/nonexistent/python3: not an executable file" \
  "$out/wp.csv" --out "$out/none4"
exit $missing
