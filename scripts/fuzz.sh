#!/usr/bin/env bash
# A longer fuzz campaign than the test suite's (tests/fuzz/README.md): each target (the
# case-set reader, the settings reader, the command line; the record reader, the external
# answer reader, the adapter's case documents and the Python keywords; issue 46's report inputs,
# Python callables, persistent external programs and the physical flags of `run`) runs for --seconds,
# from --seed, and every failing input of a new kind is written to --failures for the corpus.
#   scripts/fuzz.sh [--seconds N] [--seed S] [--build-dir DIR] [--failures DIR]
# Exit 0 when nothing was found, 1 otherwise. A finding is reproduced alone with the line
# it prints (POUNDBENCH_FUZZ_SEED=S POUNDBENCH_FUZZ_INDEX=I ...).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60 seed=$(date +%s) build=build failures=fuzz-failures
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --build-dir) build=$2; shift 2 ;;
    --failures) failures=$2; shift 2 ;;
    *) echo "usage: scripts/fuzz.sh [--seconds N] [--seed S] [--build-dir DIR] [--failures DIR]" >&2; exit 2 ;;
  esac
done

targets="poundbench poundbench_fuzz_tests"
if [ "$(cmake --build "$build" --target help | grep -c poundbench_python)" -gt 0 ]; then targets="$targets poundbench_python"; fi
cmake --build "$build" --target $targets -j2 > /dev/null
echo "fuzz: seed $seed, $seconds s per target, failing inputs to $failures/"
# The campaign tests only: the corpus replay is the suite's (ctest -L fuzz).
POUNDBENCH_FUZZ_SEED=$seed POUNDBENCH_FUZZ_SECONDS=$seconds POUNDBENCH_FUZZ_MAX_FAILURES=1000 \
  POUNDBENCH_FUZZ_FAILURES=$failures \
  "$build/tests/fuzz/poundbench_fuzz_tests" \
  --gtest_filter='CaseSetReaderFuzz.*:SettingsReaderFuzz.*:CliFuzz.*:RecordReaderFuzz.*:AnswerReaderFuzz.*:AdapterDocumentFuzz.*:PythonKeywordFuzz.*:ReportInputFuzz.*:PythonCallableFuzz.*:PhysicalFlagFuzz.*:PersistentProgramFuzz.*'
