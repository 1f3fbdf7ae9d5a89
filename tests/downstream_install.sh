#!/usr/bin/env bash
# cmake --install of BUILD_DIR into a temporary prefix, then examples/downstream configured and
# built against it alone (find_package(poundbench), CMAKE_PREFIX_PATH = the prefix): its Pi1 of
# the case must be `poundbench run`'s, digit for digit; a component the installation lacks must
# stop its configure, naming it.
#   tests/downstream_install.sh BUILD_DIR SOURCE_DIR POUNDBENCH
set -euo pipefail
build=$1 src=$2 pb=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
test -f "$tmp/prefix/include/poundbench/kit/solver.hpp"
test -x "$tmp/prefix/bin/poundbench"

# The installed `poundbench report` runs the generator installed beside it (its README names
# the generator it was made by): a spectrum of one family, reported.
cat > "$tmp/one.toml" <<'EOF2'
name = "one"
[[family]]
name = "wall"
scene = "wall"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi2 = { from = 0.5, to = 2, points = 3, spacing = "log" }
EOF2
"$tmp/prefix/bin/poundbench" spectrum "$tmp/one.toml" --out "$tmp/one.csv" 2> /dev/null
"$tmp/prefix/bin/poundbench" report "$tmp/one.csv" --out "$tmp/one-report" > /dev/null
test -s "$tmp/one-report/figures/spectrum-wall.png"
grep -q 'id="report-data"' "$tmp/one-report/report.html"
grep -q "$tmp/prefix/share/poundbench/reports/report.py" "$tmp/one-report/README.md" ||
  { echo "the installed poundbench report did not run the installed generator" >&2; exit 1; }

generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
configure() { cmake -S "$src/examples/downstream" -B "$tmp/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
                    -DCMAKE_PREFIX_PATH="$tmp/prefix" "$@"; }
configure -DPOUNDBENCH_PARTS="" > "$tmp/configure.log"
cmake --build "$tmp/build" > "$tmp/build.log"
got=$("$tmp/build/solve_case" | head -1)
want=$("$pb" run --scene pair --pulse cosine --directivity normal --pi2 0.8 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 1 \
       --json | /usr/bin/python3 -c 'import json, sys; d = json.load(sys.stdin); print(d["status"], repr(d["pi1"]))')
# %.17g and Python's repr may spell one double differently: compare the numbers read back.
/usr/bin/python3 - "$got" "$want" <<'PY'
import sys
got, want = sys.argv[1].split(), sys.argv[2].split()
assert got[0] == want[0] and float(got[1]) == float(want[1]), f"downstream {got} != poundbench run {want}"
print(f"downstream solve_case: {got[0]} {got[1]} (poundbench run: {want[1]})")
PY

# The parts it has are found; one it lacks stops the configure with its name.
parts=$(sed -n 's/^-- poundbench parts: //p' "$tmp/configure.log")
rm -rf "$tmp/build"
configure -DPOUNDBENCH_PARTS="$parts" > /dev/null
rm -rf "$tmp/build"
if configure -DPOUNDBENCH_PARTS="NoSuchPart" > "$tmp/missing.log" 2>&1; then
  echo "a missing component did not stop the configure" >&2
  exit 1
fi
grep -q "poundbench was built without NoSuchPart" "$tmp/missing.log" || { cat "$tmp/missing.log" >&2; exit 1; }
echo "components: ${parts}; a missing one is refused"
