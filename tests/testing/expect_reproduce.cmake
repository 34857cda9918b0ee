# RapidCheck's reproduce= as its documentation says: the failure's RC_PARAMS="reproduce=...",
# pasted without --gtest_filter, fails the one test it names with the same counterexample and
# skips every other test (none fails with "no implementation ran").
# cmake -DBINARY=... -DREPORTS=... -P expect_reproduce.cmake
set(ENV{OBLIQUE_IMPL} mistake_camera_space_signs)
set(ENV{OBLIQUE_REPORT_DIR} "${REPORTS}")
execute_process(COMMAND "${BINARY}" --gtest_filter=PropertiesDouble.farPlanePassesThroughTheFarCorner
                OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT output MATCHES "RC_PARAMS=\"(reproduce=[^\"]+)\"")
  message(FATAL_ERROR "the failure printed no reproduce= string:\n${output}")
endif()
set(ENV{RC_PARAMS} "${CMAKE_MATCH_1}")
execute_process(COMMAND "${BINARY}" RESULT_VARIABLE result OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "reproduce= did not reproduce the failure:\n${output}")
endif()
if(NOT output MATCHES "\\[  FAILED  \\] 1 test, listed below:\n\\[  FAILED  \\] PropertiesDouble\\.farPlanePassesThroughTheFarCorner\n")
  message(FATAL_ERROR "reproduce= should fail exactly the test it names:\n${output}")
endif()
if(NOT output MATCHES "\\[  PASSED  \\] 0 tests" OR NOT output MATCHES "\\[  SKIPPED \\] 26 tests")
  message(FATAL_ERROR "reproduce= should skip every other test:\n${output}")
endif()
message(STATUS "reproduce= fails the one test it names and skips the other 26")
