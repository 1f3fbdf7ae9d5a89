#!/usr/bin/env bash
# Shows that a new solver is one folder, one registry row and one facts row (issues 40, 47; see
# examples/new_solver/README.md): the committed tree exported into a scratch directory, the
# example solver added there as solvers/symplectic_euler with its two rows, nothing else
# touched (git says so), then the test program built and the solver contract run on it, with
# the solver's own tests and its own setting (--passes), declared in its folder alone.
#   scripts/new_solver_check.sh [SCRATCH_DIR]     (default: build-new-solver/ here)
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$src/build-new-solver}
example=$src/examples/new_solver
rm -rf "$dir"
mkdir -p "$dir"
git -C "$src" archive HEAD | tar -x -C "$dir"
cd "$dir"
git init -q && git add -A && git -c user.name=check -c user.email=check@localhost commit -qm tree

# Each example: its folder copied to solvers/, its registry row (its header's include, then
# the row) and its facts row added; nothing else.
for solver in symplectic_euler penalty_verlet; do
  echo "new_solver_check: adding solvers/$solver and its two rows"
  cp -r "$example/$solver" solvers/
  python3 - "$example" "$solver" <<'PY'
import sys
example, solver = sys.argv[1:]
include, *row = open(f"{example}/{solver}.registry.txt").read().splitlines(keepends=True)
text = open("solvers/registry.cpp").read()
anchor = '#include "solvers/registry.hpp"\n'
assert anchor in text, "solvers/registry.cpp: no include of its header"
text = text.replace(anchor, anchor + include, 1)
anchor = "const std::array kSolvers = {\n"
assert anchor in text, "solvers/registry.cpp: no kSolvers table"
text = text.replace(anchor, anchor + "".join(row), 1)
open("solvers/registry.cpp", "w").write(text)
facts = open(f"{example}/{solver}.facts.txt").read()
text = open("tests/solver_contract_test.cpp").read()
anchor = "  });\n  return table;\n"
assert anchor in text, "tests/solver_contract_test.cpp: no facts table"
text = text.replace(anchor, facts + anchor, 1)
open("tests/solver_contract_test.cpp", "w").write(text)
PY
done
changed=$(git status --porcelain | sort)
expected=$(printf '%s\n' " M solvers/registry.cpp" " M tests/solver_contract_test.cpp" "?? solvers/penalty_verlet/" \
           "?? solvers/symplectic_euler/" | sort)
if [ "$changed" != "$expected" ]; then
  echo "new_solver_check: the new solvers touched more than their folders and two rows each:" >&2
  echo "$changed" >&2
  exit 1
fi
echo "new_solver_check: git sees only the folders and their rows; building (a few minutes)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPOUNDBENCH_BENCH=OFF \
      ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} > build-configure.log
cmake --build build -j "$(nproc)" --target poundbench_tests poundbench poundbench_python > build.log
echo "new_solver_check: the solver contract on both, and symplectic-euler's own tests (its folder's *_test.cpp)"
build/tests/poundbench_tests --gtest_filter='*symplectic_euler*:*penalty_verlet*:SymplecticEuler.*'
echo "new_solver_check: its own setting as a flag (--passes), and refused for another solver"
build/poundbench run --solver symplectic-euler --passes 3 --scene row3 --pulse cosine --directivity normal --pi2 1 --pi3 0.5 \
    --eps 0.5 --pi5 0.5 --pi6 1 --pi7 0.5 --pi8 1 | grep -q '"passes":3\|passes 3'
if build/poundbench run --solver moreau-jean --passes 3 --scene wall --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 2> own.err; then
  echo "new_solver_check: --passes was accepted by moreau-jean" >&2
  exit 1
fi
grep -q 'passes: not used by solver moreau-jean' own.err
echo "new_solver_check: its own setting as a Python keyword"
PYTHONPATH=build/python python3 -c '
import poundbench
case = dict(scene="wall", pulse="sine", directivity="normal", pi2=1, pi3=0.5, eps=0.5)
assert poundbench.run(solver="symplectic-euler", passes=3, **case)["status"] == "ok"
try:
    poundbench.run(solver="moreau-jean", passes=3, **case)
    raise SystemExit("passes accepted for moreau-jean")
except ValueError as e:
    assert "passes: not used by solver moreau-jean" in str(e), e
'
echo "new_solver_check: passed"
