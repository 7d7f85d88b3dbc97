# The map of the tests: every CTest entry has labels and a timeout, set with pounding_test_map().
#
# Labels (`ctest -L LABEL` runs one kind, `-LE LABEL` leaves it out; docs/guide/development.md):
#   unit        a C++ test executable: closed forms and small scenes in one process
#   cli         the command-line program, run as a user runs it (shell or Python driving it)
#   peer        against an independent computation (scipy, sharing no code with the program)
#   validation  a validation manifest through `pounding verify`, or a validation suite
#   python      the Python module and pounding.sweep (pytest)
#   docs        the documentation: links, the site, the generated tables
#   install     cmake --install and pip install, used from outside the tree
#   fuzz        the fuzz targets' kept inputs, replayed
#   slow        minutes under the sanitizers (over ~20 s in Release): the sanitizer pass leaves
#               these out (scripts/run-sanitized-tests.sh); the Release pass runs them
#
# TIMEOUT is in seconds for the Release build on this project's 2-core machine with the suite
# running two at a time (a few times the measured time, so a slow CI machine passes and a hang
# fails in minutes rather than at CTest's default of 25). Instrumented builds multiply it by
# POUNDING_TEST_TIMEOUT_FACTOR.
set(POUNDING_TEST_KINDS unit cli peer validation python docs install fuzz)
if(POUNDING_SANITIZE OR POUNDING_BUILD_FUZZERS)
  set(POUNDING_TEST_TIMEOUT_FACTOR 10)
else()
  set(POUNDING_TEST_TIMEOUT_FACTOR 1)
endif()

# pounding_test_map(NAME... LABELS kind [slow] TIMEOUT seconds)
function(pounding_test_map)
  cmake_parse_arguments(PARSE_ARGV 0 map "" "TIMEOUT" "LABELS")
  set(names ${map_UNPARSED_ARGUMENTS})
  if(NOT names OR NOT map_LABELS OR NOT map_TIMEOUT)
    message(FATAL_ERROR "pounding_test_map(${ARGV}): needs test names, LABELS and TIMEOUT")
  endif()
  set(kinds ${map_LABELS})
  list(FILTER kinds INCLUDE REGEX "^(${POUNDING_TEST_KINDS_REGEX})$")
  if(NOT kinds)
    message(FATAL_ERROR "pounding_test_map(${ARGV}): LABELS needs one of ${POUNDING_TEST_KINDS}")
  endif()
  math(EXPR timeout "${map_TIMEOUT} * ${POUNDING_TEST_TIMEOUT_FACTOR}")
  set_tests_properties(${names} PROPERTIES LABELS "${map_LABELS}" TIMEOUT ${timeout})
endfunction()
list(JOIN POUNDING_TEST_KINDS "|" POUNDING_TEST_KINDS_REGEX)

# Fails the configuration if a test of the calling directory has no labels or no timeout: each
# CMakeLists.txt that registers tests calls it last (CMake 3.25 reads a test's properties only in
# its own directory).
function(pounding_check_test_map)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(test IN LISTS tests)
    get_test_property(${test} LABELS labels)
    get_test_property(${test} TIMEOUT timeout)
    if(NOT labels OR NOT timeout)
      message(FATAL_ERROR "test ${test} has no labels or no timeout: give it pounding_test_map() (cmake/testing.cmake)")
    endif()
  endforeach()
endfunction()
