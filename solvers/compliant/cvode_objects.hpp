#pragma once
// The SUNDIALS objects of one CVODE run and the name of a CVODE return flag, shared by the
// compliant solver's single oscillators (cvode_run.cpp) and its buildings
// (buildings_cvode.cpp).

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <cstdlib>
#include <string>

#include "kit/run_limits.hpp"
#include "kit/solver.hpp"

namespace pb::compliant {

inline std::string flag_name(int flag) {
  char* text = CVodeGetReturnFlagName(flag);
  std::string out = text ? text : std::to_string(flag);
  std::free(text);
  return out;
}

// The SUNDIALS objects of one run, released in order whatever happens.
struct Cvode {
  SUNContext context = nullptr;
  N_Vector y = nullptr, dky = nullptr;
  SUNMatrix band = nullptr;
  SUNLinearSolver linear = nullptr;
  void* mem = nullptr;
  ~Cvode() {
    if (mem) CVodeFree(&mem);
    if (linear) SUNLinSolFree(linear);
    if (band) SUNMatDestroy(band);
    if (dky) N_VDestroy(dky);
    if (y) N_VDestroy(y);
    if (context) SUNContext_Free(&context);
  }
};

// The step cap and the time limit of a run after `steps` CVODE steps: false, with the status
// and its message set in `res` (a Result or a buildings result), once one has passed.
template <class R>
bool within_limits(long steps, long cap, Deadline& deadline, double t, R& res) {
  if (steps > cap) {
    res.status = Status::step_cap;
    res.message = "more than " + std::to_string(cap) + " CVODE steps";
    return false;
  }
  if (deadline.passed(steps)) {
    res.status = Status::time_limit;
    res.message = deadline.reason() + " at t = " + std::to_string(t);
    return false;
  }
  return true;
}

}  // namespace pb::compliant
