# Configures tests/package/subproject (a parent that adds oblique with add_subdirectory) with every
# combination of OBLIQUE_BUILD_TESTS, OBLIQUE_BUILD_CLI, OBLIQUE_BUILD_BENCH and OBLIQUE_FUZZ, and
# with and without a build type of the parent's own; each must configure.
# cmake -DSOURCE=... -DWORK=... -P subproject_test.cmake
set(failures "")
foreach(tests ON OFF)
  foreach(cli ON OFF)
    foreach(bench ON OFF)
      foreach(fuzz ON OFF)
        set(combo "TESTS=${tests} CLI=${cli} BENCH=${bench} FUZZ=${fuzz}")
        file(REMOVE_RECURSE "${WORK}")
        execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE}/tests/package/subproject" -B "${WORK}"
                                -DOBLIQUE_SOURCE=${SOURCE} -DOBLIQUE_BUILD_TESTS=${tests}
                                -DOBLIQUE_BUILD_CLI=${cli} -DOBLIQUE_BUILD_BENCH=${bench}
                                -DOBLIQUE_FUZZ=${fuzz} -DCMAKE_BUILD_TYPE=Debug
                        RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
        if(result EQUAL 0)
          message(STATUS "${combo}: configures")
        else()
          string(APPEND failures "${combo}:\n${output}\n")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE}/tests/package/subproject" -B "${WORK}"
                        -DOBLIQUE_SOURCE=${SOURCE}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  string(APPEND failures "no build type:\n${output}\n")
endif()
if(failures)
  message(FATAL_ERROR "${failures}")
endif()
