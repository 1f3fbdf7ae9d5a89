# The optional parts of poundbench::core as components of find_package(poundbench): each is
# compiled into the one library when its engine is found (a solver and its registry row),
# so a component is not a target of its own but a part the installed library has, and
# what a project that links it must find too.
#
#   find_package(poundbench REQUIRED COMPONENTS ODE Bullet)   # fails if a part was left out
#   if(poundbench_Siconos_FOUND) ...                          # or asks
#
# A part is declared in one line, below the targets it changes (CMakeLists.txt):
#
#   poundbench_component(NAME DEFINITION FIND)
#
# NAME is the component's name; DEFINITION the compile definition that says the part was
# built (POUNDBENCH_HAVE_ODE), looked for on poundbench_core and poundbench_processes;
# FIND the CMake code that poundbenchConfig.cmake runs to find what the part links (its
# imported targets), "" when it links plain files.
define_property(GLOBAL PROPERTY POUNDBENCH_COMPONENTS BRIEF_DOCS "parts built" FULL_DOCS "poundbench_component")
define_property(GLOBAL PROPERTY POUNDBENCH_COMPONENT_FIND BRIEF_DOCS "their finding" FULL_DOCS "poundbench_component")

function(poundbench_component name definition find)
  set(built OFF)
  foreach(target IN ITEMS poundbench_core poundbench_processes)
    if(NOT TARGET ${target})
      continue()
    endif()
    foreach(property IN ITEMS COMPILE_DEFINITIONS INTERFACE_COMPILE_DEFINITIONS)
      get_target_property(definitions ${target} ${property})
      if(definitions AND definition IN_LIST definitions)
        set(built ON)
      endif()
    endforeach()
  endforeach()
  if(built)
    set_property(GLOBAL APPEND PROPERTY POUNDBENCH_COMPONENTS ${name})
    set_property(GLOBAL APPEND_STRING PROPERTY POUNDBENCH_COMPONENT_FIND "# ${name}\n${find}\n")
  endif()
endfunction()

# Writes and installs the package: poundbench::core (and poundbench::processes, the MPI
# sweeps), the headers under include/poundbench (included as "cases/case.hpp", as inside
# the project), poundbenchConfig.cmake with the parts declared above.
function(poundbench_install_package)
  include(GNUInstallDirs)
  include(CMakePackageConfigHelpers)
  set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/poundbench)
  set_target_properties(poundbench_core PROPERTIES EXPORT_NAME core)
  set_target_properties(poundbench_processes PROPERTIES EXPORT_NAME processes)
  install(TARGETS poundbench_core poundbench_processes EXPORT poundbenchTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(TARGETS poundbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # The report generator that `poundbench report` runs (app/report_command.hpp), and the
  # header whose tolerances its stress section quotes (reports/stability.py).
  install(DIRECTORY reports/ DESTINATION ${CMAKE_INSTALL_DATADIR}/poundbench/reports
          FILES_MATCHING PATTERN "*.py" PATTERN "page.js" PATTERN "page.css" PATTERN "paper" EXCLUDE
          PATTERN "figures" EXCLUDE PATTERN "__pycache__" EXCLUDE)
  install(FILES studies/stress.hpp DESTINATION ${CMAKE_INSTALL_DATADIR}/poundbench/studies)
  install(DIRECTORY cases programs kit solvers sweep rows studies DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/poundbench
          FILES_MATCHING PATTERN "*.hpp")
  install(EXPORT poundbenchTargets NAMESPACE poundbench:: DESTINATION ${config_dir})
  get_property(POUNDBENCH_COMPONENTS GLOBAL PROPERTY POUNDBENCH_COMPONENTS)
  get_property(POUNDBENCH_COMPONENT_FIND GLOBAL PROPERTY POUNDBENCH_COMPONENT_FIND)
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/poundbenchConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/poundbenchConfig.cmake INSTALL_DESTINATION ${config_dir})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/poundbenchConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/poundbenchConfig.cmake ${PROJECT_BINARY_DIR}/poundbenchConfigVersion.cmake
          DESTINATION ${config_dir})
  message(STATUS "poundbench package components: ${POUNDBENCH_COMPONENTS}")
endfunction()
