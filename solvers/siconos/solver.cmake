# The siconos solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
# Siconos (Debian's libsiconos-kernel-dev). Its CMake package file cannot be used: it requires
# /usr/bin/siconos, which only the Python package installs, and stops configuring without it.
# So the headers and libraries are found by name. Only engine.cpp here includes
# Siconos' headers: as SYSTEM includes (they are not clean under this project's warnings),
# and as C++17, because the Boost uBLAS they use (1.74) does not compile as C++20.
find_path(SICONOS_KERNEL_INCLUDE_DIR SiconosKernel.hpp PATH_SUFFIXES siconos/kernel)
find_path(SICONOS_NUMERICS_INCLUDE_DIR SiconosNumerics.h PATH_SUFFIXES siconos/numerics)
find_path(SICONOS_CONFIG_INCLUDE_DIR SiconosConfig.h PATH_SUFFIXES siconos)
find_path(SICONOS_SUITESPARSE_INCLUDE_DIR cs.h PATH_SUFFIXES suitesparse)
find_library(SICONOS_KERNEL_LIBRARY siconos_kernel)
find_library(SICONOS_NUMERICS_LIBRARY siconos_numerics)
poundbench_solver_sources(POUNDBENCH_SICONOS_SOURCES ${CMAKE_CURRENT_LIST_DIR})
list(FILTER POUNDBENCH_SICONOS_SOURCES EXCLUDE REGEX "/engine\\.cpp$")
set(POUNDBENCH_HAVE_SICONOS OFF)
if(POUNDBENCH_WITH_SICONOS AND SICONOS_KERNEL_INCLUDE_DIR AND SICONOS_NUMERICS_INCLUDE_DIR AND SICONOS_CONFIG_INCLUDE_DIR
   AND SICONOS_SUITESPARSE_INCLUDE_DIR AND SICONOS_KERNEL_LIBRARY AND SICONOS_NUMERICS_LIBRARY
   AND EXISTS ${CMAKE_CURRENT_LIST_DIR}/engine.cpp)
  set(POUNDBENCH_HAVE_SICONOS ON)
  add_library(poundbench_siconos_engine OBJECT ${CMAKE_CURRENT_LIST_DIR}/engine.cpp)
  # One file: a unity build (scripts/setup.sh) has nothing to merge here.
  set_target_properties(poundbench_siconos_engine PROPERTIES CXX_STANDARD 17 POSITION_INDEPENDENT_CODE ON UNITY_BUILD OFF)
  target_include_directories(poundbench_siconos_engine PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_include_directories(poundbench_siconos_engine SYSTEM PRIVATE ${SICONOS_KERNEL_INCLUDE_DIR}
                             ${SICONOS_NUMERICS_INCLUDE_DIR} ${SICONOS_CONFIG_INCLUDE_DIR}
                             ${SICONOS_SUITESPARSE_INCLUDE_DIR})
  target_link_libraries(poundbench_siconos_engine PRIVATE poundbench_warnings)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_SICONOS_SOURCES} $<TARGET_OBJECTS:poundbench_siconos_engine>)
  target_link_libraries(poundbench_core PUBLIC ${SICONOS_KERNEL_LIBRARY} ${SICONOS_NUMERICS_LIBRARY})
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_SICONOS)
  message(STATUS "Siconos found (${SICONOS_KERNEL_LIBRARY}): solver siconos, its tests and benchmark are built")
elseif(NOT POUNDBENCH_WITH_SICONOS)
  message(STATUS "Siconos left out (POUNDBENCH_WITH_SICONOS=OFF): solver siconos, its tests and benchmark are not built")
else()
  message(STATUS "Siconos not found (Debian: libsiconos-kernel-dev): solver siconos, its tests and benchmark "
                 "are left out")
endif()
