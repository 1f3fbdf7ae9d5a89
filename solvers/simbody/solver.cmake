# The simbody solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
# Simbody (Debian's libsimbody-dev 3.7), through its CMake package. Its libSimTKmath exports
# an old SUNDIALS of its own under SUNDIALS' C names (N_VNew_Serial, BandGBTRF, ... 101 of
# them) with other signatures: linked before Debian's SUNDIALS, the compliant solver's CVODE
# calls would reach them (CVodeSetLinearSolver then fails). So this file is included after
# solvers/compliant's (the folders come in name order), and SUNDIALS', whose libraries then come first in every program's search order; Simbody's own
# copy is used only by its CPodesIntegrator, which this project does not use. Only
# model.cpp here includes Simbody's headers: as C++17 (they are not valid C++20:
# ambiguous rewritten comparisons in ContactGeometry.h) and without NDEBUG in every build type
# (Debian built the library without it, and the layout of SimTK's State cache entries depends
# on it).
find_package(Simbody CONFIG QUIET)
poundbench_solver_sources(POUNDBENCH_SIMBODY_SOURCES ${CMAKE_CURRENT_LIST_DIR})
list(FILTER POUNDBENCH_SIMBODY_SOURCES EXCLUDE REGEX "/model\\.cpp$")
set(POUNDBENCH_HAVE_SIMBODY OFF)
if(Simbody_FOUND AND TARGET SimTKsimbody AND POUNDBENCH_SIMBODY_SOURCES
   AND EXISTS ${CMAKE_CURRENT_LIST_DIR}/model.cpp)
  set(POUNDBENCH_HAVE_SIMBODY ON)
  add_library(poundbench_simbody_model OBJECT ${CMAKE_CURRENT_LIST_DIR}/model.cpp)
  # One file: a unity build (scripts/setup.sh) has nothing to merge here.
  set_target_properties(poundbench_simbody_model PROPERTIES CXX_STANDARD 17 POSITION_INDEPENDENT_CODE ON UNITY_BUILD OFF)
  target_compile_options(poundbench_simbody_model PRIVATE -UNDEBUG)
  target_include_directories(poundbench_simbody_model PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(poundbench_simbody_model PRIVATE SimTKsimbody poundbench_warnings)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_SIMBODY_SOURCES} $<TARGET_OBJECTS:poundbench_simbody_model>)
  target_link_libraries(poundbench_core PRIVATE SimTKsimbody)
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_SIMBODY)
  message(STATUS "Simbody found (${Simbody_VERSION}): solver simbody, its tests and benchmark are built")
else()
  message(STATUS "Simbody not found (Debian: libsimbody-dev): solver simbody, its tests and benchmark are left out")
endif()
