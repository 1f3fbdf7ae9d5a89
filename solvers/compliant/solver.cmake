# The compliant solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
# SUNDIALS (Debian's libsundials-dev) for the compliant solver's CVODE integrator: the solver
# is left out without it, as the engines are.
find_package(SUNDIALS CONFIG QUIET)
poundbench_solver_sources(POUNDBENCH_COMPLIANT_SOURCES ${CMAKE_CURRENT_LIST_DIR})
set(POUNDBENCH_HAVE_SUNDIALS OFF)
if(SUNDIALS_FOUND AND TARGET SUNDIALS::cvode AND POUNDBENCH_COMPLIANT_SOURCES)
  set(POUNDBENCH_HAVE_SUNDIALS ON)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_COMPLIANT_SOURCES})
  target_link_libraries(poundbench_core PUBLIC SUNDIALS::cvode SUNDIALS::nvecserial SUNDIALS::sunmatrixband
                                               SUNDIALS::sunlinsolband)
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_SUNDIALS)
  message(STATUS "SUNDIALS found (${SUNDIALS_VERSION}): solver compliant is built")
else()
  message(STATUS "SUNDIALS not found (Debian: libsundials-dev): solver compliant is left out")
endif()
