#pragma once
// `poundbench report STUDY.csv [--points POINTS.csv] --out DIR`: a study's report (markdown,
// figures, an HTML page that works offline), written by the report generator of reports/
// (Python with Debian's matplotlib), the one the main job's report is made with. This
// command finds the generator and an interpreter and hands over to them:
//
//   - the generator: installed beside the binary by `cmake --install` (bin/poundbench and
//     share/poundbench/reports/report.py), else the source tree this binary was built from
//     (a build directory's binary);
//   - the interpreter: $POUNDBENCH_PYTHON when set, else Debian's /usr/bin/python3 (the one
//     scripts/setup.sh gives matplotlib; a python3 earlier in PATH, a pyenv one, may lack
//     it), else python3 on PATH.
//
// Exit codes: the generator's (0 written; 2 a bad input file, or an input that the report
// would overwrite in --out, one line naming it and nothing written; 1 an error of the
// generator itself, one line saying where), 1 when no interpreter, no generator or no
// matplotlib is found (one line saying which and how to get it). The generator writes the
// report into a folder of its own and moves it into --out (reports/out_folder.py).

#include <string>

#include <CLI/CLI.hpp>

namespace pb::app {

struct ReportFlags {
  std::string study;
  std::string points;
  std::string out;
  std::string title;
};

CLI::App* add_report_command(CLI::App& app, ReportFlags& flags);
int report_command(const ReportFlags& flags);

}  // namespace pb::app
