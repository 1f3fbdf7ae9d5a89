# Read by ctest (a TEST_INCLUDE_FILES script, tests/CMakeLists.txt): one test per parametrized
# suite and parameter, "Registry/SolverContract/ode_default" for the filter
# Registry/SolverContract.*/ode_default, where gtest_discover_tests makes one per test. A
# test is a process, and a process of poundbench_tests spends some 30 ms loading the engines'
# libraries: 788 such tests (a solver's 17 contract tests, 42 solvers) spent 23 s of CPU
# starting, half what their tests take. A failure in a group names its test in the output, as
# gtest prints it.
#   tests_exe: the test program (set by the file that includes this one)
execute_process(COMMAND "${tests_exe}" --gtest_list_tests "--gtest_filter=*/*"
                OUTPUT_VARIABLE listing ERROR_VARIABLE listing_error RESULT_VARIABLE listed TIMEOUT 60)
if(NOT listed EQUAL 0)
  # No tests to add: a test that fails in their place, saying why.
  add_test(ParamGroups.Listing sh -c "echo '${tests_exe} --gtest_list_tests: exit ${listed}'; exit 1")
  return()
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(filters "")
foreach(line IN LISTS lines)
  if(line MATCHES "^([^ ]+)\\.$")
    set(suite "${CMAKE_MATCH_1}")
  elseif(line MATCHES "^  [^ /]+/([^ ]+)")
    list(APPEND filters "${suite}.*/${CMAKE_MATCH_1}")
  endif()
endforeach()
list(REMOVE_DUPLICATES filters)
foreach(filter IN LISTS filters)
  string(REPLACE ".*/" "/" name "${filter}")
  add_test("${name}" "${tests_exe}" "--gtest_filter=${filter}")
  set_tests_properties("${name}" PROPERTIES ENVIRONMENT OPENBLAS_NUM_THREADS=1)
endforeach()
