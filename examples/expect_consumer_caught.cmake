# Runs one test of example_consumers_wrong and passes only when it fails on PROPERTY and writes a
# report naming it, with its replay command.
# cmake -DBINARY=... -DTEST=Suite.Name -DPROPERTY=... -DREPORTS=... -P expect_consumer_caught.cmake
file(REMOVE_RECURSE "${REPORTS}")
set(ENV{OBLIQUE_REPORT_DIR} "${REPORTS}")
execute_process(COMMAND "${BINARY}" --gtest_filter=${TEST}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "${TEST} passed: the consumer properties should have caught it:\n${output}")
endif()
if(NOT output MATCHES "violates ${PROPERTY} violated")
  message(FATAL_ERROR "${TEST} failed, but not on ${PROPERTY}:\n${output}")
endif()
file(GLOB reports "${REPORTS}/*.md")
if(NOT reports)
  message(FATAL_ERROR "${TEST} was caught but no report was written:\n${output}")
endif()
list(GET reports 0 first)
file(READ "${first}" text)
if(NOT text MATCHES "# Counterexample: ${PROPERTY}" OR NOT text MATCHES "## Replay")
  message(FATAL_ERROR "the report ${first} does not name ${PROPERTY} or has no replay:\n${text}")
endif()
message(STATUS "${TEST}: caught by ${PROPERTY}; report ${first}")
