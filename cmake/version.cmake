# Writes OUT, the C++ source of app/version.hpp: VERSION (project(VERSION)) and the commit
# of SOURCE_DIR. It runs at every build (the poundbench_version target), so a new commit or
# an edit since the configure is seen without one; file(CONFIGURE) rewrites OUT only when
# its text changes, so an unchanged commit recompiles nothing.
#
#   cmake -DSOURCE_DIR=... -DOUT=... -DVERSION=... -P cmake/version.cmake
set(commit "unknown")
# Only SOURCE_DIR's own checkout: a source tree unpacked inside another repository is not
# that repository's commit. --no-optional-locks: a build must never take the index lock
# from someone committing in the same tree.
execute_process(COMMAND git -C "${SOURCE_DIR}" rev-parse --show-toplevel
                OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE failed ERROR_QUIET)
if(NOT failed)
  file(REAL_PATH "${top}" top)
  file(REAL_PATH "${SOURCE_DIR}" source)
endif()
if(NOT failed AND top STREQUAL source)
  execute_process(COMMAND git -C "${SOURCE_DIR}" rev-parse --short HEAD
                  OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE failed ERROR_QUIET)
  if(NOT failed AND NOT head STREQUAL "")
    set(commit "${head}")
    execute_process(COMMAND git --no-optional-locks -C "${SOURCE_DIR}" status --porcelain --untracked-files=no
                    OUTPUT_VARIABLE changes RESULT_VARIABLE failed ERROR_QUIET)
    if(NOT failed AND NOT changes STREQUAL "")
      string(APPEND commit " (with uncommitted changes)")
    endif()
  endif()
endif()
file(CONFIGURE OUTPUT "${OUT}" CONTENT [[
// Written by cmake/version.cmake at every build; not in the source tree.
#include "app/version.hpp"

namespace pb::app {

const char* const kVersion = "@VERSION@";
const char* const kCommit = "@commit@";

}  // namespace pb::app
]] @ONLY)
