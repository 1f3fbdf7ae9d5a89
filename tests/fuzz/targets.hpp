#pragma once
// The fuzz targets issue 33 added to issue 15's: the surfaces its hostile campaign reached
// and the fuzzer did not.
//
// * record: parse_record on a mutated record file (AT2 or CSV); returns, or throws
//   RecordError with one line of at most kMaxMessage characters starting with the file.
// * answer: the external solver's answer reader (programs::read_answer) on a mutated
//   answer; returns "" or "answer: ..." in one line, and an accepted ok answer has a finite
//   Pi1 >= 0 taken within the run (t_max in [0, t_end + a step]).
// * document: the adapter's side (programs::read_case), then a solve of what it accepted by
//   one of the registry's solvers, on a mutated case document; read_case returns or throws
//   std::invalid_argument in one line, and the solver returns (any status) with an ok run's
//   Pi1 finite: no crash, no abort, no hang.
// * python: the Python module's keywords (poundbench.run, poundbench.spectrum) mutated: a
//   result, or ValueError or TypeError with a one-line message; never another exception
//   (RuntimeError, OverflowError, SystemError), a crash or a hang.
//
// Every input runs in a child process (child.hpp), as the others do.

#include <optional>
#include <string>
#include <vector>

#include "tests/fuzz/child.hpp"
#include "tests/fuzz/mutator.hpp"

namespace pb::fuzz {

enum class Document { record, answer, case_document };

// The property `text` violates when read as `kind`, or nothing. A case document accepted is
// solved by one solver chosen by the text, or by every solver of the build.
std::optional<std::string> check_document(Document kind, const std::string& text, const ChildLimits& limits,
                                          bool every_solver = false);
// The seeds: shipped records (the synthetic ones and a few real ones, shortened), answers
// and case documents written by poundbench's own writers for cases of every scene and load.
std::vector<std::string> document_seeds(Document kind);
// `seed` changed by one to four mutations of its numbers, lines, keys and bytes.
std::string mutate_document(Document kind, std::string_view seed, const std::vector<std::string>& seeds, Rng& rng);

// The Python target, when the module is built (POUNDBENCH_PYTHON_DIR): the keywords as the
// text of a Python dict (evaluated with nan, inf and Path known), "__function__" naming
// run or spectrum.
bool python_available();
std::optional<std::string> check_python(const std::string& keywords, const ChildLimits& limits);
std::vector<std::string> python_seeds();
std::string mutate_python(std::string_view seed, Rng& rng);

}  // namespace pb::fuzz
