#pragma once
// The physical-units target of issue 46 (item 8): `poundbench run` with a case given by its
// physical quantities (cases/physical.hpp: --t0 .. --uy, --m0 .. --m2, --gap, with --a-p and
// --tp or --w-p, and --k-contact), the surface whose hostile campaign found `--uy0 nan` run as
// if not given, a bad value named by the Pi flag it maps to (`--t0 1e-308` said --pi2), and
// `--m0 1e308` through the compliant solver end ok with contact_force_max null. The command
// line campaign (harness.hpp) never reached these flags.
//
// An input is a `run` command line (the corpus's .args form), built from a scene, a pulse (a
// record, rec.at2, now and then), a solver (the reference, Moreau-Jean, compliant, with
// --k-contact or without), and the physical flags the scene uses, each left out now and then
// (a missing companion: --t0 without --gap, --a-p without --tp) or given a hostile value: nan,
// inf, -inf, 1e-308, 1e308, 5e-324, 1e-300, 1e300, negatives, zero; and now and then a flag
// the scene does not use. `--json` and `--time-limit 2` always.
//
// The property: exit 0, 1 or 2 within the limits, never a signal or a sanitizer report;
//   * on 2: stderr is one line "poundbench: --FLAG: reason" naming a flag the command line
//     gave, or one it lacks with "required"; stdout empty; no file left behind;
//   * a physical value outside its field's domain (NaN anywhere; a negative; infinity but for
//     a yield displacement, which is elastic; zero but for the gap) must exit 2;
//   * on 0 or 1: stdout is one JSON object, exit 0 exactly when its status is ok; and an ok
//     row has a finite Pi1 >= 0 and peak_m, a contact force (contact_force_max) when the
//     solver is compliant, and impact_velocity a number exactly when impact_velocity_pi is.

#include <optional>
#include <string>
#include <vector>

#include "tests/fuzz/child.hpp"
#include "tests/fuzz/mutator.hpp"

namespace pb::fuzz {

// A `run` command line in physical units (without the program name), from rng alone.
std::vector<std::string> make_physical_args(Rng& rng);

// The property the run of `args` violates (in a fresh directory holding rec.at2), or nothing.
std::optional<std::string> check_physical(const std::vector<std::string>& args, const ChildLimits& limits);

}  // namespace pb::fuzz
