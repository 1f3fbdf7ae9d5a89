#!/usr/bin/env bash
# The paper report script (reports/paper/make_paper.py) on the paper's own case sets: every
# figure it should draw exists, README.md shows it, and the summary and claims tables have
# their six rows.
# The sweeps take about a second on 2 cores; drawing the figures takes the rest.
#   paper_report_smoke.sh POUNDBENCH SOURCE_DIR
set -euo pipefail
pb=$1 src=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$pb" spectrum "$src/cases/sets/paper.toml" --out "$out/paper.csv"
"$pb" spectrum "$src/cases/sets/paper-report.toml" --out "$out/extra.csv"
/usr/bin/python3 "$src/reports/paper/make_paper.py" "$out/paper.csv" "$out/extra.csv" --poundbench "$pb" \
  --out "$out/report" > /dev/null
missing=0
for fig in fig3-self-similarity fig4-normal fig5-reverse pi5-limit fig6-time-histories fig7-two-sided regions \
           fig8-mass-stiff fig9-mass-flexible fig10-scaling; do
  for ext in png svg; do
    [ -s "$out/report/figures/$fig.$ext" ] || { echo "missing figure $fig.$ext"; missing=1; }
  done
  grep -q "(figures/$fig.png)" "$out/report/README.md" || { echo "README.md does not show $fig"; missing=1; }
done
claims=$(grep -c '^| [0-9] | ' "$out/report/README.md" || true)
[ "$claims" -eq 6 ] || { echo "claims table has $claims rows, not 6"; missing=1; }
# The page opens with the summary: claim (a link to its section), whether it holds, evidence.
summary=$(sed -n '/^## /q; /^| claim | holds? | evidence |$/,/^$/p' "$out/report/README.md" |
  grep -c '^| \[[^]]*\](#[a-z0-9-]*) | \(yes\|\*\*partly\*\*\|\*\*no\*\*\) | ' || true)
[ "$summary" -eq 6 ] || { echo "summary table has $summary rows, not 6"; missing=1; }
exit $missing
