# The mujoco solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out, saying so, without it.
# MuJoCo (Debian's libmujoco-dev). Its CMake package wants OpenGL's development files
# (find_dependency(OpenGL): libgl-dev, libglx-dev, libopengl-dev) and names qhull's headers
# (/usr/include/libqhull_r: libqhull-dev) among its include directories, though this
# project uses neither; without them find_package fails and the solver is left out.
find_package(mujoco CONFIG QUIET)
poundbench_solver_sources(POUNDBENCH_MUJOCO_SOURCES ${CMAKE_CURRENT_LIST_DIR})
set(POUNDBENCH_HAVE_MUJOCO OFF)
set(POUNDBENCH_MUJOCO_INCLUDES_EXIST ON)
if(TARGET mujoco::mujoco)
  get_target_property(POUNDBENCH_MUJOCO_INCLUDES mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
  foreach(dir IN LISTS POUNDBENCH_MUJOCO_INCLUDES)
    if(NOT EXISTS "${dir}")
      set(POUNDBENCH_MUJOCO_INCLUDES_EXIST OFF)
    endif()
  endforeach()
endif()
if(mujoco_FOUND AND TARGET mujoco::mujoco AND POUNDBENCH_MUJOCO_INCLUDES_EXIST AND POUNDBENCH_MUJOCO_SOURCES)
  set(POUNDBENCH_HAVE_MUJOCO ON)
  target_sources(poundbench_core PRIVATE ${POUNDBENCH_MUJOCO_SOURCES})
  target_link_libraries(poundbench_core PUBLIC mujoco::mujoco)
  target_compile_definitions(poundbench_core PUBLIC POUNDBENCH_HAVE_MUJOCO)
  message(STATUS "MuJoCo found (${mujoco_VERSION}): solver mujoco, its tests and benchmark are built")
else()
  message(STATUS "MuJoCo not found (Debian: libmujoco-dev): solver mujoco, its tests and benchmark are left out")
endif()
