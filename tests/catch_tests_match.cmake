# catch_tests_match.cmake: every Catch2 test case runs as exactly one CTest test.
#
#   cmake -DTEST_EXE=<clraster_tests> -DCTEST=<ctest> -DBUILD_DIR=<build> -P catch_tests_match.cmake
#
# Reads the test cases from `TEST_EXE --list-test-names-only` and the CTest tests
# that run TEST_EXE from `ctest --show-only=json-v1`. Fails, naming the test, when
# a CTest test's argument selects anything but its own one test case (a name that
# catch_discover_tests split, or a spec that matches nothing and "passes" with
# "No tests ran"), when a test case has no CTest test, or when one has two.
# Names are handled as strings, never as CMake lists, so a ';' cannot hide.

foreach(var TEST_EXE CTEST BUILD_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "catch_tests_match: -D${var}= is required")
  endif()
endforeach()

execute_process(COMMAND "${TEST_EXE}" --list-test-names-only OUTPUT_VARIABLE cases RESULT_VARIABLE rc)
if(cases STREQUAL "")
  message(FATAL_ERROR "catch_tests_match: ${TEST_EXE} lists no test cases (exit ${rc})")
endif()
execute_process(COMMAND "${CTEST}" --test-dir "${BUILD_DIR}" --show-only=json-v1
                OUTPUT_VARIABLE json RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "catch_tests_match: ctest --show-only=json-v1 failed (exit ${rc})")
endif()

set(failures "")
set(seen "\n") # "\n"-delimited names of the CTest tests that run TEST_EXE
string(JSON count LENGTH "${json}" tests)
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON exe ERROR_VARIABLE err GET "${json}" tests ${i} command 0)
  if(err OR NOT exe STREQUAL TEST_EXE)
    continue()
  endif()
  string(JSON name GET "${json}" tests ${i} name)
  string(JSON nargs LENGTH "${json}" tests ${i} command)
  if(NOT nargs EQUAL 2)
    string(APPEND failures "CTest test '${name}' runs ${TEST_EXE} with ${nargs} words, not one test spec\n")
    continue()
  endif()
  string(JSON spec GET "${json}" tests ${i} command 1)
  string(FIND "${seen}" "\n${name}\n" dup)
  if(NOT dup EQUAL -1)
    string(APPEND failures "two CTest tests are named '${name}'\n")
  endif()
  string(APPEND seen "${name}\n")
  string(FIND "${spec}" ";" semicolon)
  if(NOT semicolon EQUAL -1)
    string(APPEND failures "CTest test '${name}': its spec contains ';', which CMake splits\n")
    continue()
  endif()
  execute_process(COMMAND "${TEST_EXE}" --list-test-names-only "${spec}" OUTPUT_VARIABLE selected)
  if(NOT selected STREQUAL "${name}\n")
    string(REPLACE "\n" " | " shown "${selected}")
    string(APPEND failures "CTest test '${name}' selects [${shown}] instead of exactly its own test case\n")
  endif()
endforeach()

# Every test case has a CTest test: walk the listing line by line, as strings.
set(rest "${cases}")
set(ncases 0)
while(NOT rest STREQUAL "")
  string(FIND "${rest}" "\n" eol)
  if(eol EQUAL -1)
    set(line "${rest}")
    set(rest "")
  else()
    string(SUBSTRING "${rest}" 0 ${eol} line)
    math(EXPR next "${eol} + 1")
    string(SUBSTRING "${rest}" ${next} -1 rest)
  endif()
  if(line STREQUAL "")
    continue()
  endif()
  math(EXPR ncases "${ncases} + 1")
  string(FIND "${seen}" "\n${line}\n" found)
  if(found EQUAL -1)
    string(APPEND failures "test case '${line}' has no CTest test of its own (does its name contain ';'?)\n")
  endif()
endwhile()

if(NOT failures STREQUAL "")
  message(FATAL_ERROR "catch_tests_match: Catch2 test cases and CTest tests differ:\n${failures}")
endif()
message(STATUS "catch_tests_match: ${ncases} test cases, each one CTest test")
