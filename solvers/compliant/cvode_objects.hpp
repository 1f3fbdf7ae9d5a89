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

}  // namespace pb::compliant
