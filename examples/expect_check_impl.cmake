# `oblique check SCENE --impl IMPL [ARGS]` exits with EXIT (a crash is never an exit status) and
# its output contains MATCH.
execute_process(COMMAND ${OBLIQUE} check ${SCENE} --impl ${IMPL} ${ARGS}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${result}" STREQUAL "${EXIT}")
  message(FATAL_ERROR "oblique check --impl ${IMPL} ${ARGS} ${SCENE}: exit ${result}, expected ${EXIT}\n${out}\n${err}")
endif()
string(FIND "${out}" "${MATCH}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "oblique check: the output lacks \"${MATCH}\"\n${out}\n${err}")
endif()
