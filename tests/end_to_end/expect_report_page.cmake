cmake_minimum_required(VERSION 3.25)
# cmake -DOBLIQUE=... -DIMPL=... -DREPORTS=dir -P expect_report_page.cmake: verify catches IMPL,
# and the report's page (STEM.html) passes the browser check (html_view_check.cmake): loaded in
# headless Chromium on WebGL2 and on the plain canvas, no console error, every layer seen, a
# toggle that changes the picture. "browser check skipped" (a CTest skip) without Chromium.
include(${CMAKE_CURRENT_LIST_DIR}/html_view_check.cmake)
file(REMOVE_RECURSE "${REPORTS}")
execute_process(COMMAND "${OBLIQUE}" verify --impl "${IMPL}" --report-dir "${REPORTS}" --quiet
                        --seed 1 --time-limit 20
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 1)
  message(FATAL_ERROR "html view: oblique verify exited with ${result}, expected 1:\n${output}${errors}")
endif()
file(GLOB pages "${REPORTS}/verify-*.html")
list(LENGTH pages count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "html view: expected one page in ${REPORTS}, found ${count}")
endif()
file(READ "${pages}" page_text)
foreach(part "<canvas" "data:image/png;base64," "Counterexample:" "## Replay")
  string(FIND "${page_text}" "${part}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "html view: the page lacks '${part}'")
  endif()
endforeach()
# Self-contained: nothing fetched from elsewhere.
if(page_text MATCHES "(src|href)=\"(https?:)?//")
  message(FATAL_ERROR "html view: the page loads something from the network")
endif()
check_html_view("${pages}")
