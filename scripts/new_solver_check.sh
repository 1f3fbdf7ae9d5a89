#!/usr/bin/env bash
# Shows that a new solver is one folder, one registry row and one facts row (issue 40; see
# examples/new_solver/README.md): the committed tree exported into a scratch directory, the
# example solver added there as solvers/symplectic_euler with its two rows, nothing else
# touched (git says so), then the test program built and the solver contract run on it.
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

echo "new_solver_check: adding solvers/symplectic_euler and its two rows"
cp -r "$example/symplectic_euler" solvers/
python3 - "$example" <<'PY'
import sys
example = sys.argv[1]
include, *row = open(f"{example}/registry_row.txt").read().splitlines(keepends=True)
text = open("solvers/registry.cpp").read()
text = text.replace('#include "solvers/solver.hpp"\n', '#include "solvers/solver.hpp"\n' + include, 1)
anchor = "const std::array kSolvers = {\n"
assert anchor in text, "solvers/registry.cpp: no kSolvers table"
text = text.replace(anchor, anchor + "".join(row), 1)
open("solvers/registry.cpp", "w").write(text)
facts = open(f"{example}/facts_row.txt").read()
text = open("tests/solver_contract_test.cpp").read()
anchor = "  });\n  return table;\n"
assert anchor in text, "tests/solver_contract_test.cpp: no facts table"
text = text.replace(anchor, facts + anchor, 1)
open("tests/solver_contract_test.cpp", "w").write(text)
PY
changed=$(git status --porcelain | sort)
expected=$(printf '%s\n' " M solvers/registry.cpp" " M tests/solver_contract_test.cpp" "?? solvers/symplectic_euler/" | sort)
if [ "$changed" != "$expected" ]; then
  echo "new_solver_check: the new solver touched more than its folder and two rows:" >&2
  echo "$changed" >&2
  exit 1
fi
echo "new_solver_check: git sees only the folder and the two rows; building (a few minutes)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPOUNDBENCH_BENCH=OFF \
      ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} > build-configure.log
cmake --build build -j "$(nproc)" --target poundbench_tests poundbench > build.log
echo "new_solver_check: the solver contract on symplectic-euler"
build/tests/poundbench_tests --gtest_filter='*symplectic_euler*'
