# The engine idioms of the oblique matrix (examples/engine_matrices/idioms.txt, docs/engines.md):
# each right function passes every way in (verify over the protocol in float, the property test
# in its own storage), each wrong twin is caught and named by both. The campaign
# (scripts/false_alarms.sh) runs the right ones at fresh seeds.
set(matrix_idioms ${PROJECT_SOURCE_DIR}/examples/engine_matrices)
file(STRINGS ${matrix_idioms}/idioms.txt matrix_idiom_lines REGEX "^[a-z]")
foreach(line ${matrix_idiom_lines})
  string(REPLACE "|" ";" fields "${line}")
  list(GET fields 0 name)
  list(GET fields 2 convention)
  list(GET fields 3 families)
  list(GET fields 4 names_twin)
  set(claims --preset engine --precision float --convention ${convention} --families ${families})
  add_test(NAME matrix_idiom_verify_right_${name}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "no violation"
                   $<TARGET_FILE:oblique> verify ${claims} --impl "${examples_dir}/example_engine_matrices ${name}"
                   --time-limit 5 --seed 20261207
                   --report-dir ${PROJECT_BINARY_DIR}/verify_reports/matrix_idioms_right)
  add_test(NAME matrix_idiom_verify_wrong_${name}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 1 "likely cause.*${names_twin}"
                   $<TARGET_FILE:oblique> verify ${claims}
                   --impl "${examples_dir}/example_engine_matrices ${name}_wrong"
                   --time-limit 30 --seed 20261207
                   --report-dir ${PROJECT_BINARY_DIR}/verify_reports/matrix_idioms_wrong_${name})
  add_test(NAME matrix_idiom_test_right_${name}
           COMMAND example_engine_matrices_test --gtest_filter=RightMatrices.${name})
  add_test(NAME matrix_idiom_test_wrong_${name}
           COMMAND ${CMAKE_COMMAND} -DBINARY=$<TARGET_FILE:example_engine_matrices_test>
                   -DTEST=WrongMatrices.${name} "-DCAUSE=${names_twin}"
                   -DREPORTS=${PROJECT_BINARY_DIR}/matrix_idiom_reports/${name}
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/expect_property_test_caught.cmake)
  set_tests_properties(matrix_idiom_verify_right_${name} matrix_idiom_verify_wrong_${name}
                       matrix_idiom_test_right_${name} matrix_idiom_test_wrong_${name}
                       PROPERTIES LABELS "idioms;matrices" TIMEOUT 90
                       ENVIRONMENT "RC_PARAMS=seed=20261207")
  # A route that loses bits shows on deep frustums, a few in a hundred cases: the wrong twins'
  # property runs draw a thousand (each still under a second).
  set_tests_properties(matrix_idiom_test_wrong_${name} PROPERTIES
                       ENVIRONMENT "RC_PARAMS=seed=20261207 max_success=1000")
endforeach()
# A row-vector function declared as M by rows is named as the layout, not a formula mistake.
add_test(NAME matrix_idiom_test_undeclared_layout_named_transposed
         COMMAND ${CMAKE_COMMAND} -DBINARY=$<TARGET_FILE:example_engine_matrices_test>
                 -DTEST=UndeclaredLayout.d3d_left_handed -DCAUSE=transposed_layout
                 -DREPORTS=${PROJECT_BINARY_DIR}/matrix_idiom_reports/undeclared_layout
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/expect_property_test_caught.cmake)
set_tests_properties(matrix_idiom_test_undeclared_layout_named_transposed PROPERTIES
                     LABELS "idioms;matrices" TIMEOUT 90 ENVIRONMENT "RC_PARAMS=seed=20261207")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${matrix_idioms}/idioms.txt)
# The fuzz driver: every right idiom on mutated corpus inputs, no finding; each twin alone, caught.
add_test(NAME matrix_idiom_fuzz_right
         COMMAND example_engine_matrices_fuzz_replay --random 100000 --seed 20261207
                 ${PROJECT_SOURCE_DIR}/fuzz/corpus/fuzz_oblique)
set_tests_properties(matrix_idiom_fuzz_right PROPERTIES LABELS "idioms;matrices;fuzz" TIMEOUT 120)
foreach(line ${matrix_idiom_lines})
  string(REPLACE "|" ";" fields "${line}")
  list(GET fields 0 name)
  add_test(NAME matrix_idiom_fuzz_wrong_${name}
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 134 "oblique property violated"
                   env OBLIQUE_IDIOM=${name}_wrong
                   $<TARGET_FILE:example_engine_matrices_fuzz_replay> --random 1000000 --seed 20261207
                   ${PROJECT_SOURCE_DIR}/fuzz/corpus/fuzz_oblique)
  set_tests_properties(matrix_idiom_fuzz_wrong_${name} PROPERTIES LABELS "idioms;matrices;fuzz"
                       TIMEOUT 120)
endforeach()
# The Direct3D-style engine end to end (docs/engines.md): row vectors, [0, 1], left-handed, its
# mirror pass flipping x (examples/scenes/d3d_wall_mirror.json, "mirror_flip": "projection_x").
# check builds the mirror pass as the engine does and asks its function: the right one passes,
# the one whose bug lives on the mirror path only (OpenGL's factor there) is caught; its HLSL
# reconstruction (row vectors) is judged on the same passes.
# The program answers the matrix (--consumers none: the scene's reconstruction is the shader's).
oblique_check_impl_test(d3d_engine_mirror_pass_passes d3d_wall_mirror.json
                        "${examples_dir}/example_engine_matrices d3d_mirror_pass" 0 "wall mirror: pass"
                        ARGS --consumers none --precision float)
oblique_check_impl_test(d3d_engine_mirror_path_bug_caught d3d_wall_mirror.json
                        "${examples_dir}/example_engine_matrices d3d_mirror_pass_wrong" 1
                        "wall mirror: FAIL" ARGS --consumers none --precision float)
# --consumers names only what the scene names, or none.
add_test(NAME check_consumers_refuses_one_the_scene_does_not_name
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 2 "names no consumer culling"
                 $<TARGET_FILE:oblique> check ${PROJECT_SOURCE_DIR}/examples/scenes/d3d_wall_mirror.json
                 --consumers culling)
add_test(NAME check_consumers_refuses_an_unknown_name
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 2 "unknown scene consumer"
                 $<TARGET_FILE:oblique> check ${PROJECT_SOURCE_DIR}/examples/scenes/d3d_wall_mirror.json
                 --consumers reconstrction)
set_tests_properties(check_consumers_refuses_one_the_scene_does_not_name
                     check_consumers_refuses_an_unknown_name PROPERTIES LABELS check TIMEOUT 30)
add_test(NAME check_d3d_engine_hlsl_reconstruction
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "reconstruction ok \\([1-9][0-9]* judged\\)"
                 $<TARGET_FILE:oblique> check ${PROJECT_SOURCE_DIR}/examples/scenes/d3d_wall_mirror.json
                 --vectors row
                 --shader ${PROJECT_SOURCE_DIR}/examples/shaders/engines/d3d_row_vectors.hlsl:view_position)
set_tests_properties(check_d3d_engine_hlsl_reconstruction PROPERTIES LABELS "idioms;matrices;shaders"
                     TIMEOUT 90 SKIP_REGULAR_EXPRESSION "${shader_skip}")
# The same HLSL without --vectors row is handed M, not the M^T its engine's uniforms hold: caught
# on the D3D scene's mirror pass and named as the transpose.
add_test(NAME check_d3d_engine_hlsl_undeclared_vectors_named_transposed
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 1 "likely cause: transposed_matrix"
                 $<TARGET_FILE:oblique> check ${PROJECT_SOURCE_DIR}/examples/scenes/d3d_wall_mirror.json
                 --shader ${PROJECT_SOURCE_DIR}/examples/shaders/engines/d3d_row_vectors.hlsl:view_position)
set_tests_properties(check_d3d_engine_hlsl_undeclared_vectors_named_transposed PROPERTIES
                     LABELS "idioms;matrices;shaders" TIMEOUT 90 SKIP_REGULAR_EXPRESSION "${shader_skip}")
# --layout: the row-vector engine's program takes its matrices as its engine stores them (R = M^T
# by rows) and writes them so; verify and check put every matrix in that order at its end alone.
# Declared, it passes; undeclared, its answers are the transposed use, named transposed_layout.
set(d3d_claims --preset engine --precision float --convention zero_one
               --families left_handed,left_handed_x_flipped)
add_test(NAME verify_layout_row_vectors_passes_the_stored_d3d_engine
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 0 "no violation"
                 $<TARGET_FILE:oblique> verify ${d3d_claims} --layout row_vectors
                 --impl "${examples_dir}/example_engine_matrices d3d_mirror_pass --as-stored"
                 --time-limit 5 --seed 20261207
                 --report-dir ${PROJECT_BINARY_DIR}/verify_reports/layout_row_vectors)
add_test(NAME verify_layout_undeclared_names_transposed_layout
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh 1 "likely cause: transposed_layout"
                 $<TARGET_FILE:oblique> verify ${d3d_claims}
                 --impl "${examples_dir}/example_engine_matrices d3d_mirror_pass --as-stored"
                 --time-limit 30 --seed 20261207
                 --report-dir ${PROJECT_BINARY_DIR}/verify_reports/layout_undeclared)
set_tests_properties(verify_layout_row_vectors_passes_the_stored_d3d_engine
                     verify_layout_undeclared_names_transposed_layout PROPERTIES
                     LABELS "verify;idioms;matrices" TIMEOUT 90)
oblique_check_impl_test(d3d_engine_layout_row_vectors_passes d3d_wall_mirror.json
                        "${examples_dir}/example_engine_matrices d3d_mirror_pass --as-stored" 0
                        "wall mirror: pass"
                        ARGS --consumers none --precision float --layout row_vectors)
oblique_check_impl_test(d3d_engine_layout_row_vectors_bug_caught d3d_wall_mirror.json
                        "${examples_dir}/example_engine_matrices d3d_mirror_pass_wrong --as-stored" 1
                        "wall mirror: FAIL"
                        ARGS --consumers none --precision float --layout row_vectors)
