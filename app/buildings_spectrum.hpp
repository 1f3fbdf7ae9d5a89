#pragma once
// `spectrum` over a buildings case set (cases/buildings_set.hpp): every point through a solver
// of the scene, beside the reference's no-contact response, one CSV row per floor
// (rows/buildings_rows.hpp), written whole or not at all.

#include <CLI/CLI.hpp>

#include "app/spectrum_command.hpp"
#include "cases/buildings_set.hpp"

namespace pb::app {

// Exit code as spectrum_command's; the flags of the single oscillators' sweeps that have no
// meaning here (--repetitions, --estimate-error, --target-error, --junit, --monitor) are
// refused in one line.
int buildings_spectrum(const CLI::App& command, const SpectrumFlags& flags, const BuildingsSet& set);

}  // namespace pb::app
