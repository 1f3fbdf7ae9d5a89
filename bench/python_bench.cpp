// What `poundbench.run` costs on top of its solve (issue 36: 40-50 us a call, a 0.5 us
// Moreau-Jean solve costing 50 us through Python; target under 5 us):
//
//   PythonRun   poundbench.run(...) on the Fig. 4 pair through Moreau-Jean at N = 64, called
//               from an interpreter embedded here, the module imported from the build tree.
//               CPU time per call, and fixed_cost: that call's CPU time less the solve's own
//               (moreau_jean::solve alone, bench::timed, measured right after on the same case;
//               the call asks monitor=False, so that it solves the same way):
//               the keywords' checks, the no-contact Pi1, the row and its dict. One case is
//               called again and again, so its no-contact Pi1 comes from the module's cache
//               after the first call; a call whose body 0 is new (a loop over Pi2) solves it,
//               52 k instructions more (callgrind), about 4 us here. Its keywords are classified
//               once per module, and its case's checks by name kept from the last call while
//               only values change, as in a loop over Pi terms (poundbench_module.cpp, case_of).
//
// Without the Python module (POUNDBENCH_HAVE_PYTHON) this file compiles to nothing.

#ifdef POUNDBENCH_HAVE_PYTHON

#include <benchmark/benchmark.h>
#include <pybind11/embed.h>

#include "kit/benchmarking.hpp"
#include "solvers/registry.hpp"

namespace py = pybind11;

namespace {

// The interpreter, started once and never finalised (the module's objects live to the end).
py::module_& poundbench() {
  static py::module_* module = [] {
    new py::scoped_interpreter();
    py::module_::import("sys").attr("path").attr("insert")(0, POUNDBENCH_PYTHON_DIR);
    return new py::module_(py::module_::import("poundbench"));
  }();
  return *module;
}

void BM_PythonRun(benchmark::State& state) {
  const py::object run = poundbench().attr("run");
  const pb::Case c = pb::bench::fig4_case(pb::Scene::pair);
  py::dict keywords;
  keywords["scene"] = "pair";
  keywords["pulse"] = "cosine";
  keywords["directivity"] = "normal";
  keywords["pi2"] = c.pi2;
  keywords["pi3"] = c.pi3;
  keywords["pi5"] = c.pi5;
  keywords["pi6"] = c.pi6;
  keywords["eps"] = c.eps;
  keywords["solver"] = "moreau-jean";
  keywords["steps"] = 64;
  // Solved as the subtracted solve is, unmonitored: by default run()'s one solve is monitored,
  // which is the solve's cost, not the module's (Moreau-Jean on the pair: 3.2 against 2.1 us).
  keywords["monitor"] = false;
  if (run(**keywords)["status"].cast<std::string>() != "ok") state.SkipWithError("poundbench.run did not end ok");
  const double start = pb::bench::thread_seconds();
  for (auto _ : state) benchmark::DoNotOptimize(run(**keywords).ptr());
  const double per_call = (pb::bench::thread_seconds() - start) / static_cast<double>(state.iterations());
  pb::Settings settings;
  settings.steps = 64;
  const double solve = pb::bench::seconds_per_run(pb::find_solver("moreau-jean")->solve, pb::make_system(c), settings);
  state.counters["solve"] = solve;
  state.counters["fixed_cost"] = per_call - solve;
}
BENCHMARK(BM_PythonRun)->Unit(benchmark::kMicrosecond);

}  // namespace

#endif  // POUNDBENCH_HAVE_PYTHON
