cmake_minimum_required(VERSION 3.25)
# cmake -DPAGE=page.html [-DMAKE="command;args"] -P expect_html_view.cmake: runs MAKE (which must
# write PAGE and exit 0 or 1), then the browser check of the page (html_view_check.cmake);
# "browser check skipped" where Chromium is not installed.
include(${CMAKE_CURRENT_LIST_DIR}/html_view_check.cmake)
if(MAKE)
  file(REMOVE "${PAGE}")
  execute_process(COMMAND ${MAKE} RESULT_VARIABLE result OUTPUT_VARIABLE output
                  ERROR_VARIABLE output)
  if(NOT result EQUAL 0 AND NOT result EQUAL 1)
    message(FATAL_ERROR "html view: ${MAKE} exited with ${result}:\n${output}")
  endif()
  if(NOT output MATCHES "page: ${PAGE}")
    message(FATAL_ERROR "html view: the command did not name its page ${PAGE}:\n${output}")
  endif()
endif()
check_html_view("${PAGE}")
