#!/usr/bin/env bash
# No function body in the project's own sources is longer than 100 lines (issue 47): a longer
# one is split into functions whose names say what each part does. The sources are the files
# git tracks (nothing generated is tracked), else those under SOURCE_DIR outside build
# directories.
#   C++: a body is the lines between the line of the function's name and that of its closing
#   brace, as universal-ctags finds them (its end field); a lambda's lines count in the
#   function around it. The measure is first tried on a probe, a function at the limit and one
#   that a lambda takes past it, so that a ctags that reads them otherwise fails here rather
#   than passing everything. Without universal-ctags (scripts/setup.sh installs it) this part
#   is skipped, saying so.
#   Python: the lines after the def line to the function's last, by Python's own parser; a
#   nested function's lines count in the one around it.
#   function_length.sh SOURCE_DIR
set -euo pipefail
src=$1
limit=100

# The C++ file names on stdin; "LINES lines: FILE:LINE NAME" for each body over the limit.
too_long_cpp() {
  ctags -L - --languages=C++ --kinds-C++=f --fields=+ne -x --_xformat='%{line} %{end} %{input} %{name}' |
    awk -v limit="$limit" '
      $2 !~ /^[0-9]+$/ { print "no end found: " $3 ":" $1 " " $4; next }
      $2 - $1 - 1 > limit { print $2 - $1 - 1 " lines: " $3 ":" $1 " " $4 }'
}

# The same for the Python file names on stdin.
too_long_python() {
  /usr/bin/python3 -c '
import ast, sys
limit = int(sys.argv[1])
for path in sys.stdin.read().split():
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.end_lineno - node.lineno > limit:
            print(f"{node.end_lineno - node.lineno} lines: {path}:{node.lineno} {node.name}")
' "$limit"
}

# The tracked files of these patterns, else those found outside build directories.
sources() {
  if [ "$(git rev-parse --show-toplevel 2>/dev/null)" = "$(pwd -P)" ]; then
    git ls-files "$@"
  else
    local names=() p
    for p in "$@"; do names+=(-o -name "$p"); done
    find . \( -name '.git' -o -name 'build*' \) -prune -o -type f \( "${names[@]:1}" \) -print | sed 's|^\./||'
  fi
}

cd "$src"
cpp=$(sources '*.cpp' '*.hpp' '*.h' '*.cc' '*.cxx')
python=$(sources '*.py')
if [ -z "$cpp" ] || [ -z "$python" ]; then
  echo "function_length: FAILED: no C++ or no Python source found in $src"
  exit 1
fi
long=$(echo "$python" | too_long_python)

ctags_found=0
if ctags --version 2>/dev/null | grep -q 'Universal Ctags'; then
  ctags_found=1
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  {
    echo 'int at_the_limit() {'
    for i in $(seq "$limit"); do echo "  int x$i = $i;"; done
    echo '}'
    echo 'int past_it_by_a_lambda() {'
    echo '  const auto f = [] {'
    for i in $(seq $((limit - 2))); do echo "    int x$i = $i;"; done
    echo '  };'
    echo '  return f();'
    echo '}'
  } > "$tmp/probe.cpp"
  probe=$(echo "$tmp/probe.cpp" | too_long_cpp)
  if [ "$probe" != "$((limit + 1)) lines: $tmp/probe.cpp:$((limit + 3)) past_it_by_a_lambda" ]; then
    echo "function_length: FAILED: the measure misreads its probe (a body of $limit lines, one of $((limit + 1))"
    echo "with a lambda); it reported: ${probe:-nothing}"
    exit 1
  fi
  long=$(printf '%s\n%s' "$long" "$(echo "$cpp" | too_long_cpp)")
fi

long=$(echo "$long" | sed '/^$/d' | sort -rn)
if [ -n "$long" ]; then
  echo "function_length: FAILED: function bodies over $limit lines (split each into functions that say what each"
  echo "part does):"
  echo "$long"
  exit 1
fi
if [ "$ctags_found" = 0 ]; then
  echo "function_length: $(echo "$python" | wc -l) Python files, no function body over $limit lines; the C++ sources"
  echo "skipped: universal-ctags not found (scripts/setup.sh installs universal-ctags)"
  exit 77
fi
echo "function_length: $(echo "$cpp" | wc -l) C++ and $(echo "$python" | wc -l) Python files, no function body over" \
     "$limit lines"
