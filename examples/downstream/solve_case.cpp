// A program of another project that links poundbench::core (examples/downstream/CMakeLists.txt):
// one case of the paper's Fig. 4 family solved by the reference, and a small spectrum over
// Pi2 by a sweep on every core. Prints "status pi1" of the case on its first line, with every
// digit, then "pi2 pi1" per point of the spectrum.

#include <cstdio>
#include <vector>

#include "cases/case.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "sweep/sweep.hpp"

int main() {
  pb::Case c;
  c.scene = pb::Scene::pair;
  c.pulse = pb::PulseShape::cosine;
  c.directivity = pb::Directivity::normal;
  c.pi2 = 0.8;
  c.pi3 = 0.5;
  c.eps = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  if (const auto bad = pb::validate(c)) {
    std::fprintf(stderr, "solve_case: %s\n", bad->c_str());
    return 2;
  }
  const pb::SolverInfo& reference = pb::reference_solver();
  const pb::Result r = reference.solve(pb::make_system(c), pb::Settings{});
  std::printf("%s %.17g\n", std::string(pb::name(r.status)).c_str(), r.pi1);

  std::vector<pb::Case> spectrum;
  for (double pi2 : {0.25, 0.5, 1.0, 2.0, 4.0}) {
    spectrum.push_back(c);
    spectrum.back().pi2 = pi2;
  }
  for (const pb::Row& row : pb::run_sweep(spectrum, reference, pb::Settings{}))
    std::printf("%g %.17g\n", row.input.pi2, row.result.pi1);
  return r.status == pb::Status::ok ? 0 : 1;
}
