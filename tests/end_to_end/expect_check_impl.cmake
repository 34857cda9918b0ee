# `oblique check SCENE --impl IMPL [ARGS]` exits with EXIT (a crash is never an exit status) and
# its output (standard output, or standard error for exit 2) contains MATCH.
# Without IMPL: `oblique check SCENE [ARGS]`.
set(impl_args "")
if(NOT "${IMPL}" STREQUAL "")
  set(impl_args --impl ${IMPL})
endif()
execute_process(COMMAND ${OBLIQUE} check ${SCENE} ${impl_args} ${ARGS}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${result}" STREQUAL "${EXIT}")
  message(FATAL_ERROR "oblique check --impl ${IMPL} ${ARGS} ${SCENE}: exit ${result}, expected ${EXIT}\n${out}\n${err}")
endif()
if("${EXIT}" STREQUAL "2")
  string(FIND "${err}" "${MATCH}" at)
else()
  string(FIND "${out}" "${MATCH}" at)
endif()
if(at EQUAL -1)
  message(FATAL_ERROR "oblique check: the output lacks \"${MATCH}\"\n${out}\n${err}")
endif()
