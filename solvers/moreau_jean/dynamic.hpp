#pragma once
// The Moreau-Jean step loop for any number of bodies in a row (a chain of up to
// kMaxChainBodies, a wall and several bodies, ...): the same scheme and the same
// arithmetic as the fixed-size loop of stepper.hpp, on vectors sized once per run.
//
// Bodies couple only through contacts, and contact j only through its two bodies, so the
// active contacts of a step fall into runs of consecutive contacts; different runs share
// no body, and each run's Newton LCP is solved on its own. One or two contacts are solved
// in closed form (lcp::solve1, lcp::solve2, as in the fixed-size loop); a longer run, whose
// matrix W^T M_hat^-1 W is a tridiagonal Stieltjes matrix, by TridiagonalLcp (exact, O(n)
// per pass; see tridiagonal_lcp.hpp for why not Lemke).
//
// Body arrays have one slot before body 0 (slot 0): the wall when there is one, otherwise
// a slot that no contact uses. Its coefficients and its M_hat^-1 are 0, so it stays at rest
// whatever impulse it takes, and contact j always joins slots first + j and first + j + 1
// (first = 0 with a wall, 1 without): no branch for the wall in the loop.
//
// Everything is allocated by make_work() and make_state(); a step allocates nothing.

#include <Eigen/Core>
#include <vector>

#include "cases/system.hpp"
#include "solvers/moreau_jean/loop_common.hpp"
#include "solvers/moreau_jean/tridiagonal_lcp.hpp"
#include "kit/monitor.hpp"

namespace pb::moreau_jean::dynamic {

// What a run never changes.
struct Scheme {
  int nb = 0, nc = 0;  // bodies, contacts
  int first = 1;       // slot of the left body of contact 0
  int ref = 1;         // slot of body 0, the reference
  double h = 0.0;
  double gamma_h = 0.0;  // gamma h
  double eps = 0.0;
  double delta = 0.0;  // gap of every contact at rest
  double bound = 0.0;  // |u| above this is divergence
  // Per slot (nb + 1), as in stepper.hpp: v_free = fv .* v + fq .* q + fa abar and
  // q_free = qv .* v + qq .* q + qa abar; minv = M_hat^-1, h_minv = h theta M_hat^-1.
  Eigen::VectorXd fv, fq, fa, qv, qq, qa, minv, h_minv;
  // W^T M_hat^-1 W: diag (nc) and off (nc, off(j) = A(j, j+1) = -minv of their shared
  // body; the last entry is unused).
  Eigen::VectorXd diag, off;
  PulseLoad load;
};

Scheme make_scheme(const System& s, double h, double theta, double gamma, LoadRule load = LoadRule::step_mean);

struct State {
  Eigen::VectorXd q, v;  // per slot: q is u, the displacement
  Eigen::VectorXd g, rate;  // per contact: gaps and gap rates W^T v
  std::vector<char> active;    // in the index set of the last step
  std::vector<char> pushed;    // positive impulse in the last step
  std::vector<char> in_phase;  // in a persistent-contact phase
  long k = 0;                  // steps taken: the state is at t_k = k h
};

// u, v: one value per body, left to right.
State make_state(const Scheme& sc, const double* u, const double* v);

// The scratch of a step.
struct Work {
  Eigen::VectorXd v_new, q_new;  // per slot
  Eigen::VectorXd rhs, impulse;  // per contact: the LCP's q, and P
  TridiagonalLcp lcp;
  long lcp_passes = 0;  // tridiagonal solves so far (runs of 3 or more contacts)
};

Work make_work(const Scheme& sc);

// The start of a run on this loop: the state from the System's start values (rest where it
// gives none), its tally, and where rows is given the history's first row (room reserved
// for n steps, the layout set in res.history).
State start_run(const Scheme& sc, const System& sys, long n, const Work& w, Tally& tally, Result& res,
                std::vector<double>* rows);

// Steps until st.k == k_end; false if the run blew up (st is left at the bad step).
// history (one row per step, room reserved) and monitor may be null.
bool advance(const Scheme& sc, State& st, Work& w, Tally& t, long k_end, std::vector<double>* history,
             StepMonitor* monitor);

// The two halves of a step around its free motion, for a loop that forms the free motion
// itself (yielding.cpp): `contacts` takes w.v_new, w.q_new (the free motion) to the motion
// with the step's impulses, and counts impacts and phases into t; `finish_step` moves the
// state there and tallies it (no monitor); false if the run blew up.
void contacts(const Scheme& sc, State& st, Work& w, Tally& t);
bool finish_step(const Scheme& sc, State& st, Work& w, Tally& t, std::vector<double>* history);

// One history row of the state (t, u, v, g, lambda = P / h).
void record(const Scheme& sc, const State& st, const Eigen::VectorXd& impulse, std::vector<double>& out);

}  // namespace pb::moreau_jean::dynamic
