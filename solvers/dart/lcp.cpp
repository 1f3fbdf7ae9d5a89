#include "solvers/dart/lcp.hpp"

#include <cmath>
#include <cstdarg>
#include <mutex>

#include <dart/external/odelcpsolver/error.h>

namespace pb::dart {

namespace {

thread_local long t_messages = 0;

void count_message(int, const char*, va_list) { ++t_messages; }

}  // namespace

void prepare_process() {
  static std::once_flag once;
  std::call_once(once, [] { ::dart::external::ode::dSetMessageHandler(&count_message); });
}

long lcp_messages() { return t_messages; }

bool CountingDantzig::solve(int n, double* A, double* x, double* b, int nub, double* lo, double* hi, int* findex,
                            bool earlyTermination) {
  if (limit) limit->tick();
  const bool ok = DantzigBoxedLcpSolver::solve(n, A, x, b, nub, lo, hi, findex, earlyTermination);
  bool finite = true;
  for (int i = 0; i < n; ++i) finite = finite && !std::isnan(x[i]);
  if (!ok || !finite) ++failures;
  return ok;
}

bool CountingPgs::solve(int n, double* A, double* x, double* b, int nub, double* lo, double* hi, int* findex,
                        bool earlyTermination) {
  if (limit) limit->tick();
  ++calls;
  const bool ok = PgsBoxedLcpSolver::solve(n, A, x, b, nub, lo, hi, findex, earlyTermination);
  if (!ok) ++failures;
  return ok;
}

LcpSolvers set_faithful_solver(::dart::simulation::World& world, bool pgs, int sweeps, RunLimit& limit) {
  LcpSolvers lcp;
  if (pgs) {
    lcp.pgs = std::make_shared<CountingPgs>();
    lcp.pgs->limit = &limit;
    lcp.pgs->setOption(::dart::constraint::PgsBoxedLcpSolver::Option(sweeps, 0.0, 0.0));
    world.setConstraintSolver(std::make_unique<::dart::constraint::BoxedLcpConstraintSolver>(lcp.pgs, nullptr));
  } else {
    lcp.dantzig = std::make_shared<CountingDantzig>();
    lcp.dantzig->limit = &limit;
    world.setConstraintSolver(std::make_unique<::dart::constraint::BoxedLcpConstraintSolver>(lcp.dantzig, nullptr));
  }
  return lcp;
}

}  // namespace pb::dart
