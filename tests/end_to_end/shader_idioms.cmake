# The engine idioms of depth reconstruction (examples/shaders/engines/idioms.txt, docs/shaders.md):
# each right function passes every way in (verify --shader, check --shader, OBLIQUE_SHADER_TEST),
# each wrong twin is caught and named by what its answers show (verify and OBLIQUE_SHADER_TEST).
# The campaign (scripts/false_alarms.sh) runs the right ones at fresh seeds. Included by
# CMakeLists.txt after shaders.cmake (shader_skip, shader_reports).
set(idioms ${PROJECT_SOURCE_DIR}/examples/shaders/engines)
file(STRINGS ${idioms}/idioms.txt idiom_lines REGEX "^[a-z]")
foreach(line ${idiom_lines})
  string(REPLACE "|" ";" fields "${line}")
  list(GET fields 0 name)
  list(GET fields 1 file)
  list(GET fields 2 kind)
  list(GET fields 3 conventions)
  list(GET fields 4 families)
  list(GET fields 5 v)
  list(GET fields 6 vectors)
  list(GET fields 7 shows)
  string(REGEX REPLACE "\\.([a-z]+)$" "_wrong.\\1" wrong ${file})
  set(claims --consumers ${kind} --precision float --convention ${conventions})
  if(families)
    list(APPEND claims --families ${families})
  endif()
  set(way "")
  if(v)
    set(way --uv-v ${v})
  endif()
  if(vectors)
    list(APPEND way --vectors ${vectors})
  endif()
  add_test(NAME shader_idiom_verify_right_${name}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "no violation in [1-9][0-9]* answers judged"
                   $<TARGET_FILE:oblique> verify ${claims} ${way} --shader ${idioms}/${file}
                   --time-limit 2 --seed 20261207 --report-dir ${shader_reports}/idioms_right)
  add_test(NAME shader_idiom_verify_wrong_${name}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 1 "likely cause: .*${shows}"
                   $<TARGET_FILE:oblique> verify ${claims} ${way} --shader ${idioms}/${wrong}
                   --time-limit 30 --seed 20261207 --report-dir ${shader_reports}/idioms_wrong)
  # A scene's reconstruction consumer (zero_one, perspective cameras) answered by it.
  add_test(NAME shader_idiom_check_right_${name}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "reconstruction ok \\([1-9][0-9]* judged\\)"
                   $<TARGET_FILE:oblique> check ${PROJECT_SOURCE_DIR}/examples/scenes/portal_room_consumers.json
                   ${way} --shader ${idioms}/${file}:${kind})
  set_tests_properties(shader_idiom_verify_right_${name} shader_idiom_verify_wrong_${name}
                       shader_idiom_check_right_${name} PROPERTIES LABELS "shaders;idioms"
                       TIMEOUT 90 SKIP_REGULAR_EXPRESSION "${shader_skip}")
  if(TARGET example_engine_idioms)
    add_test(NAME shader_idiom_test_macro_right_${name}
             COMMAND example_engine_idioms --gtest_filter=RightIdioms.${name})
    set(named "")
    if(shows MATCHES "^[a-z_]+$")
      set(named -DCAUSE=${shows})
    else()
      set(named "-DSHOWS=${shows}")
    endif()
    add_test(NAME shader_idiom_test_macro_wrong_${name}
             COMMAND ${CMAKE_COMMAND} -DBINARY=$<TARGET_FILE:example_engine_idioms>
                     -DTEST=WrongIdioms.${name} -DPROPERTY=${kind} ${named}
                     -DREPORTS=${shader_reports}/idiom_${name}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/expect_consumer_caught.cmake)
    set_tests_properties(shader_idiom_test_macro_right_${name}
                         shader_idiom_test_macro_wrong_${name} PROPERTIES LABELS "shaders;idioms"
                         TIMEOUT 90 ENVIRONMENT "RC_PARAMS=seed=20261207;OBLIQUE_REPORT_DIR=${shader_reports}/idiom_macro"
                         SKIP_REGULAR_EXPRESSION "${shader_skip}")
  endif()
endforeach()
# A row-vector engine's right function declared without its layout is handed M, not the M^T its
# uniforms hold: caught, and named as the transpose it then computes.
add_test(NAME shader_idiom_verify_row_vectors_undeclared_named_transposed
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 1 "likely cause: transposed_matrix"
                 $<TARGET_FILE:oblique> verify --consumers view_position --precision float
                 --convention all --shader ${idioms}/d3d_row_vectors.hlsl --time-limit 30
                 --seed 20261207 --report-dir ${shader_reports}/idioms_undeclared)
set_tests_properties(shader_idiom_verify_row_vectors_undeclared_named_transposed PROPERTIES
                     LABELS "shaders;idioms" TIMEOUT 90 SKIP_REGULAR_EXPRESSION "${shader_skip}")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${idioms}/idioms.txt)
