# The bullet solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
# Debian's libbullet-dev ships single (bullet) and double (bullet-float64) precision
# builds with the same symbols; one program can link only one of them.
pkg_check_modules(BULLET IMPORTED_TARGET bullet)
file(GLOB POUNDBENCH_BULLET_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
if(BULLET_FOUND AND POUNDBENCH_BULLET_SOURCES)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_BULLET_SOURCES})
  target_link_libraries(poundbench_core PUBLIC PkgConfig::BULLET)
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_BULLET)
endif()
