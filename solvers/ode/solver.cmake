# The ode solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
pkg_check_modules(ODE IMPORTED_TARGET ode)
file(GLOB POUNDBENCH_ODE_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
if(ODE_FOUND AND POUNDBENCH_ODE_SOURCES)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_ODE_SOURCES})
  target_link_libraries(poundbench_core PUBLIC PkgConfig::ODE)
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_ODE)
endif()
