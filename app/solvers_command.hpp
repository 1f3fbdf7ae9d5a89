#pragma once
// `poundbench solvers`: every solver of the registry with its variants (the default first)
// and the settings each variant uses, as aligned text or, with --json, one JSON object.

#include <CLI/CLI.hpp>

namespace pb::app {

struct SolversFlags {
  bool json = false;
};

CLI::App* add_solvers_command(CLI::App& app, SolversFlags& flags);
int solvers_command(const SolversFlags& flags);

}  // namespace pb::app
