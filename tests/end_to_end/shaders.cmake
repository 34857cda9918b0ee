# Shaders as they ship (docs/shaders.md): the bundled right and wrong depth functions, in GLSL
# and HLSL, through OBLIQUE_SHADER_TEST (example_shaders) and `oblique verify --shader`; each
# wrong one caught by its property and named, each right one passing in every convention. On a
# machine without EGL (or, for HLSL, glslang-tools and spirv-cross) they are skipped: the output
# says what to install. Included by CMakeLists.txt.
set(shaders ${PROJECT_SOURCE_DIR}/examples/shaders)
set(shader_skip "no EGL|which is not installed|\\[  SKIPPED \\]")
set(shader_reports ${PROJECT_BINARY_DIR}/shader_reports)
if(TARGET example_shaders)
  add_test(NAME shaders_right_pass COMMAND example_shaders --gtest_filter=RightShaders.*)
  set_tests_properties(shaders_right_pass PROPERTIES LABELS shaders
                       SKIP_REGULAR_EXPRESSION "${shader_skip}"
                       ENVIRONMENT "OBLIQUE_REPORT_DIR=${shader_reports}/right")
endif()
foreach(wrong CameraMatrix:camera_matrix_view_position:view_position:reconstructs_with_original
              Zparams:zparams_linear_depth:linear_depth:linearises_with_near_far
              OpenglNdc:opengl_ndc_view_position:view_position:ndc_depth_of_other_convention
              ReversedAsForward:reversed_as_forward_view_position:view_position:reads_reversed_as_forward)
  string(REPLACE ":" ";" fields ${wrong})
  list(GET fields 0 test)
  list(GET fields 1 function)
  list(GET fields 2 kind)
  list(GET fields 3 cause)
  foreach(language glsl hlsl)
    if(TARGET example_shaders)
      add_test(NAME shaders_catch_${language}${test}
               COMMAND ${CMAKE_COMMAND} -DBINARY=$<TARGET_FILE:example_shaders>
                       -DTEST=WrongShaders.${language}${test} -DPROPERTY=${kind} -DPICTURES=1
                       -DCAUSE=${cause} -DREPORTS=${shader_reports}/${language}${test}
                       -P ${CMAKE_CURRENT_SOURCE_DIR}/expect_consumer_caught.cmake)
      set_tests_properties(shaders_catch_${language}${test} PROPERTIES LABELS shaders TIMEOUT 60
                           SKIP_REGULAR_EXPRESSION "${shader_skip}")
    endif()
    # verify --shader: caught in every convention, named, reported, replayed (and the right
    # shader holds on the replay).
    add_test(NAME shaders_verify_catches_${language}${test}
             COMMAND ${CMAKE_COMMAND} -DOBLIQUE=$<TARGET_FILE:oblique>
                     -DSHADER=${shaders}/depth_wrong.${language}:${function}
                     -DRIGHT_SHADER=${shaders}/depth_right.${language}:${kind}
                     -DKINDS=${kind} -DEXIT=1 -DPROPERTY=${kind} -DPICTURES=1 -DCAUSE=${cause}
                     "-DARGS=--time-limit;30;--convention;all"
                     -DREPORTS=${shader_reports}/verify_${language}${test}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/expect_verify_consumers.cmake)
    set_tests_properties(shaders_verify_catches_${language}${test} PROPERTIES
                         LABELS "shaders;verify" TIMEOUT 120
                         SKIP_REGULAR_EXPRESSION "${shader_skip}")
  endforeach()
endforeach()
foreach(right depth_right.glsl depth_right.hlsl)
  add_test(NAME shaders_verify_right_${right}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "no violation in [1-9][0-9]* answers judged"
                   $<TARGET_FILE:oblique> verify --consumers view_position,linear_depth
                   --shader ${shaders}/${right} --convention all --time-limit 3 --seed 20261206
                   --report-dir ${shader_reports}/verify_right)
  set_tests_properties(shaders_verify_right_${right} PROPERTIES LABELS "shaders;verify" TIMEOUT 60
                       SKIP_REGULAR_EXPRESSION "${shader_skip}")
endforeach()
add_test(NAME shaders_verify_right_inverse_in_shader
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "no violation in [1-9][0-9]* answers judged"
                 $<TARGET_FILE:oblique> verify --consumers view_position
                 --shader ${shaders}/depth_right_inverse_in_shader.glsl --convention all
                 --time-limit 3 --seed 20261206 --report-dir ${shader_reports}/verify_right)
set_tests_properties(shaders_verify_right_inverse_in_shader PROPERTIES LABELS "shaders;verify"
                     TIMEOUT 60 SKIP_REGULAR_EXPRESSION "${shader_skip}")
