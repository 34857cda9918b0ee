cmake_minimum_required(VERSION 3.25)
# cmake -DPAGE=good.html -DOUT=dir -P expect_html_check_rejects.cmake: the browser check
# (html_view_check.cmake) passes PAGE and rejects each planted fault of a copy of it: a script
# that throws before anything is drawn, and a layer drawn in the background's colour (not seen).
# Each planted page is checked in a CMake run of its own (a check that fails ends its run).
if(NOT DEFINED PLANTED)
  file(MAKE_DIRECTORY "${OUT}")
  file(READ "${PAGE}" page)
  set(throws "${page}")
  string(REPLACE "\"use strict\";\n(function () {" "\"use strict\";\n(function () { planted_fault();"
                 throws "${throws}")
  set(white "${page}")
  string(REGEX REPLACE "\"color\":\\[[0-9]+,[0-9]+,[0-9]+\\]" "\"color\":[255,255,255]" white
                       "${white}")
  foreach(plant throws white)
    if("${${plant}}" STREQUAL "${page}")
      message(FATAL_ERROR "html check test: the fault '${plant}' could not be planted")
    endif()
    file(WRITE "${OUT}/${plant}.html" "${${plant}}")
    execute_process(COMMAND ${CMAKE_COMMAND} -DPLANTED=${OUT}/${plant}.html
                            -P ${CMAKE_CURRENT_LIST_FILE}
                    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
    if(output MATCHES "browser check skipped")
      message(STATUS "browser check skipped: chromium is not installed")
      return()
    endif()
    if(result EQUAL 0)
      message(FATAL_ERROR "html check test: the page with the fault '${plant}' passed:\n${output}")
    endif()
    # Rejected for its fault: the console's uncaught error; the layer not seen.
    set(reason_throws "Uncaught ReferenceError: planted_fault")
    set(reason_white "is not seen in its colour")
    string(REGEX REPLACE "[ \n]+" " " said "${output}")
    if(NOT said MATCHES "${reason_${plant}}")
      message(FATAL_ERROR "html check test: the fault '${plant}' was rejected for another reason:\n${output}")
    endif()
    message(STATUS "rejected '${plant}': ${reason_${plant}}")
  endforeach()
  include(${CMAKE_CURRENT_LIST_DIR}/html_view_check.cmake)
  check_html_view("${PAGE}")
  return()
endif()
include(${CMAKE_CURRENT_LIST_DIR}/html_view_check.cmake)
check_html_view("${PLANTED}")
