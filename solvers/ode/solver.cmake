# The ode solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out without it.
pkg_check_modules(ODE IMPORTED_TARGET ode)
poundbench_engine(ODE ODE_FOUND PUBLIC PkgConfig::ODE)
