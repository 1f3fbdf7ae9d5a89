# The dart solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
# DART (Debian's libdart-dev 6.12), through its CMake package. Debian builds it without NDEBUG,
# and the layout of some of its classes depends on NDEBUG (BoxedLcpSolver has a virtual
# canSolve only without it), so the solver's sources, which include DART's headers, are
# compiled without NDEBUG in every build type; ${CMAKE_CURRENT_LIST_DIR}/dart_solver.hpp names no DART type.
find_package(DART 6.12 CONFIG QUIET COMPONENTS dart)
poundbench_solver_sources(POUNDBENCH_DART_SOURCES ${CMAKE_CURRENT_LIST_DIR})
set(POUNDBENCH_HAVE_DART OFF)
if(DART_FOUND AND TARGET dart AND POUNDBENCH_DART_SOURCES)
  set(POUNDBENCH_HAVE_DART ON)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_DART_SOURCES})
  set_source_files_properties(${POUNDBENCH_DART_SOURCES} PROPERTIES COMPILE_OPTIONS -UNDEBUG)
  target_link_libraries(poundbench_core PRIVATE dart)
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_DART)
  message(STATUS "DART found (${DART_VERSION}): solver dart, its tests and benchmark are built")
else()
  message(STATUS "DART not found (Debian: libdart-dev): solver dart, its tests and benchmark are left out")
endif()
