# check_html_view(PAGE): loads a report's interactive page (oblique/report/html_page.h) in
# headless Chromium with #selftest, once on WebGL2 (or what the browser has) and once on the plain
# canvas (#selftest-canvas), and requires its self-test: no script error, every layer drawn in its
# colour (its pixels counted), a toggle that changes the picture. Sets HTML_VIEW_SKIPPED (and says
# why) where Chromium is not installed.
function(check_html_view page)
  find_program(OBLIQUE_CHROMIUM NAMES chromium chromium-browser google-chrome)
  if(NOT OBLIQUE_CHROMIUM)
    message(STATUS "browser check skipped: chromium is not installed (apt-get install chromium; "
                   "bash scripts/setup.sh installs it)")
    set(HTML_VIEW_SKIPPED TRUE PARENT_SCOPE)
    return()
  endif()
  if(NOT EXISTS "${page}")
    message(FATAL_ERROR "html view: no page ${page}")
  endif()
  string(RANDOM LENGTH 8 profile)
  set(profile "${CMAKE_CURRENT_BINARY_DIR}/chromium-profile-${profile}")
  foreach(mode selftest selftest-canvas)
    file(REMOVE_RECURSE "${profile}")
    execute_process(
      COMMAND "${OBLIQUE_CHROMIUM}" --headless --no-sandbox --disable-gpu
              --disable-background-networking --disable-component-update --disable-sync
              --no-first-run --user-data-dir=${profile} --virtual-time-budget=5000
              --enable-unsafe-swiftshader --enable-logging=stderr --v=0
              --dump-dom "file://${page}#${mode}"
      RESULT_VARIABLE result OUTPUT_VARIABLE dom ERROR_VARIABLE browser_log TIMEOUT 60)
    file(REMOVE_RECURSE "${profile}")
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "html view: chromium exited with ${result} on ${page}#${mode}:\n${browser_log}")
    endif()
    # The console: no uncaught error (one before the page's own listener ran, say).
    string(REGEX MATCH "\"Uncaught [^\n]*" uncaught "${browser_log}")
    if(uncaught)
      message(FATAL_ERROR "html view: ${page}#${mode}: the console says ${uncaught}")
    endif()
    string(REGEX MATCH "<pre id=\"selftest\"[^>]*>([^<]*)</pre>" found "${dom}")
    if(NOT found OR "${CMAKE_MATCH_1}" STREQUAL "")
      message(FATAL_ERROR "html view: ${page}#${mode} wrote no self-test result (a script failed "
                          "to run?):\n${browser_log}")
    endif()
    set(result_json "${CMAKE_MATCH_1}")
    string(REPLACE "&lt;" "<" result_json "${result_json}")
    string(REPLACE "&gt;" ">" result_json "${result_json}")
    string(REPLACE "&amp;" "&" result_json "${result_json}")
    string(JSON errors LENGTH "${result_json}" errors)
    if(NOT errors EQUAL 0)
      string(JSON first GET "${result_json}" errors 0)
      message(FATAL_ERROR "html view: ${page}#${mode}: ${errors} script error(s): ${first}")
    endif()
    string(JSON renderer GET "${result_json}" renderer)
    if(mode STREQUAL "selftest-canvas" AND NOT renderer STREQUAL "canvas")
      message(FATAL_ERROR "html view: #selftest-canvas drew with ${renderer}, not the canvas")
    endif()
    string(JSON layers LENGTH "${result_json}" layers)
    string(JSON nothing GET "${result_json}" nothing_to_draw)
    if(layers EQUAL 0)
      # A case with nothing to draw (M has no volume in double): the page says so, and it loaded.
      if(NOT nothing)
        message(FATAL_ERROR "html view: ${page}#${mode}: no layer is seen")
      endif()
      message(STATUS "html view ${mode} (${renderer}): nothing to draw, said; no script error")
      continue()
    endif()
    math(EXPR last "${layers} - 1")
    foreach(i RANGE ${last})
      string(JSON name MEMBER "${result_json}" layers ${i})
      string(JSON pixels GET "${result_json}" layers "${name}")
      if(NOT pixels GREATER 0)
        message(FATAL_ERROR "html view: ${page}#${mode}: the layer '${name}' is not seen in its "
                            "colour (0 pixels)")
      endif()
    endforeach()
    string(JSON before GET "${result_json}" toggle drawn_before)
    string(JSON after GET "${result_json}" toggle drawn_after)
    if(before EQUAL after)
      message(FATAL_ERROR "html view: ${page}#${mode}: hiding a layer left ${before} pixels drawn")
    endif()
    message(STATUS "html view ${mode} (${renderer}): ${layers} layers seen, a toggle changes "
                   "${before} to ${after} pixels drawn")
  endforeach()
endfunction()
