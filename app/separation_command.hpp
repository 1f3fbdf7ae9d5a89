#pragma once
// `poundbench separation CASESET`: the separation study of studies/separation_study.hpp. Every
// case through the exact reference (its rows carry the required gap and the rules' gaps), then,
// with --gap-fractions, every case again at those fractions of its required gap; the per-case
// table to --out (stdout without it), the per-family summary of each rule to --summary. A
// buildings set: a row per floor level (contact) of every point, from the reference's free
// watch, and with --gap-fractions each point again through the reference with contacts.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pb::app {

struct SeparationFlags {
  std::string case_set;
  std::string out;      // empty: stdout
  std::string summary;  // empty: not written
  std::vector<double> gap_fractions;
  unsigned threads = 0;
};

CLI::App* add_separation_command(CLI::App& app, SeparationFlags& flags);
// Exit code: 0 done (a case whose run failed is a row saying so), 130 interrupted.
int separation_command(const SeparationFlags& flags);

}  // namespace pb::app
