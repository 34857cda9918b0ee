# The downstream example (examples/downstream) against the installed package, as a user would
# build it: install this build tree into WORK/prefix, configure the example with
# -DCMAKE_PREFIX_PATH, build it, then
#  - the fixed engine passes the property suite, the raster check and its fuzz replay, and its
#    depth reconstruction the consumer properties; its accuracy profile is written beside the
#    core's methods;
#  - the engine as shipped fails the suite with a report naming make_oblique, the y-flipped
#    family and a property, and the report's replay command, pasted into a shell, fails again;
#  - the fuzz replay of the installed seed corpus catches it too, and so does the raster check
#    (the kept region clipped, with a report of the pixels);
#  - with CLANGXX, the libFuzzer target builds and, run, stops on a violation.
# cmake -DBUILD=... -DSOURCE=... -DWORK=... [-DCLANGXX=...] -P downstream_test.cmake
function(run)
  cmake_parse_arguments(R "" "EXPECT;OUTPUT;DIR" "COMMAND" ${ARGN})
  execute_process(COMMAND ${R_COMMAND} WORKING_DIRECTORY "${R_DIR}" RESULT_VARIABLE result
                  OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(R_EXPECT STREQUAL "ok" AND NOT result EQUAL 0)
    message(FATAL_ERROR "${R_COMMAND} failed (${result}):\n${output}")
  elseif(R_EXPECT STREQUAL "fail" AND result EQUAL 0)
    message(FATAL_ERROR "${R_COMMAND} should have failed:\n${output}")
  endif()
  if(R_OUTPUT)
    set(${R_OUTPUT} "${output}" PARENT_SCOPE)
  endif()
endfunction()

file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
run(EXPECT ok COMMAND ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${prefix}")
run(EXPECT ok COMMAND ${CMAKE_COMMAND} -S "${SOURCE}/examples/downstream" -B "${WORK}/gcc"
                      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(EXPECT ok COMMAND ${CMAKE_COMMAND} --build "${WORK}/gcc" -j2)

set(ENV{OBLIQUE_REPORT_DIR} "${WORK}/reports")
run(EXPECT ok COMMAND "${WORK}/gcc/engine_property_test_fixed")
run(EXPECT ok OUTPUT output COMMAND "${WORK}/gcc/engine_consumers_test")
if(NOT output MATCHES "view_position: OK, passed")
  message(FATAL_ERROR "the engine's consumer test ran no view_position property:\n${output}")
endif()
# The fixed engine's accuracy profile: its report beside the core's three methods.
run(EXPECT ok OUTPUT output COMMAND "${WORK}/gcc/engine_accuracy_test")
if(NOT output MATCHES "accuracy: [1-9][0-9]* answers profiled, worst [0-9.]+ bits lost, [0-9.]+ ns a call: ([^\n]+accuracy\\.md)")
  message(FATAL_ERROR "the engine's accuracy test wrote no profile:\n${output}")
endif()
file(READ "${CMAKE_MATCH_1}" text)
foreach(row "| make_oblique | float |" "| core closed_form | float |" "| core general | float |"
        "| core accurate | float |")
  string(FIND "${text}" "${row}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the accuracy profile has no row \"${row}\":\n${text}")
  endif()
endforeach()
run(EXPECT ok OUTPUT output COMMAND "${WORK}/gcc/engine_raster_test_fixed")
set(rasterizer ON)
if(output MATCHES "the rasterizer cannot run here: no EGL")
  set(rasterizer OFF)  # no EGL on this machine: the raster tests skip, saying so
  message(STATUS "no EGL: the raster checks are not run")
elseif(NOT output MATCHES "rasterizer: OK, passed")
  message(FATAL_ERROR "the fixed engine's raster test drew nothing:\n${output}")
endif()
run(EXPECT ok COMMAND "${WORK}/gcc/engine_fuzz_replay_fixed" "${prefix}/share/oblique/fuzz/corpus")
run(EXPECT fail OUTPUT output COMMAND "${WORK}/gcc/engine_property_test")
if(NOT output MATCHES "make_oblique violates ([a-z_]+)")
  message(FATAL_ERROR "the suite's failure names no property of make_oblique:\n${output}")
endif()
if(NOT output MATCHES "report: ([^\n]+\\.md)")
  message(FATAL_ERROR "the suite wrote no report:\n${output}")
endif()
set(report "${CMAKE_MATCH_1}")
file(READ "${report}" text)
if(NOT text MATCHES "# Counterexample: [a-z_]+ \\(make_oblique, float\\)" OR
   NOT text MATCHES "Family `y_flipped`")
  message(FATAL_ERROR "the report ${report} does not name make_oblique on a y-flipped matrix:\n${text}")
endif()
if(NOT text MATCHES "```sh\n(RC_PARAMS=[^\n]+)\n```")
  message(FATAL_ERROR "the report ${report} has no replay command:\n${text}")
endif()
set(replay "${CMAKE_MATCH_1}")
run(EXPECT fail OUTPUT output COMMAND sh -c "${replay}" DIR "${WORK}")
if(NOT output MATCHES "make_oblique violates")
  message(FATAL_ERROR "the replay command (${replay}) did not reproduce the failure:\n${output}")
endif()
run(EXPECT fail OUTPUT output COMMAND "${WORK}/gcc/engine_fuzz_replay" "${prefix}/share/oblique/fuzz/corpus")
if(NOT output MATCHES "oblique property violated: [a-z_]+ by make_oblique")
  message(FATAL_ERROR "the fuzz replay did not catch make_oblique:\n${output}")
endif()
# On the rasterizer, the shipped engine's far plane through the wrong corner clips what the
# camera sees.
if(rasterizer)
  run(EXPECT fail OUTPUT output COMMAND "${WORK}/gcc/engine_raster_test")
  if(NOT output MATCHES "make_oblique fails on the rasterizer [^\n]*: [0-9]+ samples drawn behind C, [1-9][0-9]* of the original volume on C's kept side clipped")
    message(FATAL_ERROR "the raster test did not catch make_oblique clipping the kept region:\n${output}")
  endif()
  if(NOT output MATCHES "report: ([^\n]+\\.rasterizer\\.md)")
    message(FATAL_ERROR "the raster test wrote no report:\n${output}")
  endif()
  set(raster_report "${CMAKE_MATCH_1}")
  file(READ "${raster_report}" text)
  if(NOT text MATCHES "family `y_flipped`" OR NOT text MATCHES "\\| clipped_kept \\|")
    message(FATAL_ERROR "the raster report ${raster_report} does not show a y-flipped case clipped:\n${text}")
  endif()
endif()
message(STATUS "the engine as shipped is caught (${report}, and on the rasterizer); the fixed one passes")

# Without CMake: the installed pkg-config file builds the fixed engine's property test, and the
# installed tool says its version.
find_program(PKG_CONFIG NAMES pkg-config pkgconf)
if(NOT PKG_CONFIG)
  message(FATAL_ERROR "pkg-config not found (scripts/setup.sh installs pkgconf)")
endif()
file(GLOB_RECURSE pc_file "${prefix}/*/oblique-testing.pc")
if(NOT pc_file)
  message(FATAL_ERROR "no oblique-testing.pc installed under ${prefix}")
endif()
get_filename_component(pc_dir "${pc_file}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
run(EXPECT ok OUTPUT flags COMMAND ${PKG_CONFIG} --cflags --libs oblique-testing gtest_main)
string(STRIP "${flags}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(EXPECT ok COMMAND c++ -O1 -DENGINE_FIXED=1 "${SOURCE}/examples/downstream/engine_property_test.cpp"
                      "${SOURCE}/examples/downstream/engine.cpp" ${flags} -pthread
                      -o "${WORK}/engine_property_test_pkg_config")
run(EXPECT ok COMMAND "${WORK}/engine_property_test_pkg_config")
# The flags set no language standard: a user's -std=c++20 before them stays in force (a -std in
# Cflags came after it and turned C++20 code into errors).
foreach(pc oblique oblique-testing oblique-fuzzing oblique-testing-raster)
  if(NOT EXISTS "${pc_dir}/${pc}.pc")
    continue()  # oblique-testing-raster: installed only with EGL
  endif()
  run(EXPECT ok OUTPUT pc_cflags COMMAND ${PKG_CONFIG} --cflags ${pc})
  if(pc_cflags MATCHES "-std=")
    message(FATAL_ERROR "pkg-config --cflags ${pc} sets the language standard: ${pc_cflags}")
  endif()
endforeach()
file(WRITE "${WORK}/cxx20_user.cpp" [=[
// A C++20 file of a user's that includes the suite's header: it must stay C++20.
#include "oblique/testing.h"
#include <span>
static_assert(__cplusplus >= 202002L, "the user's -std=c++20 was overridden");
template <class T> concept Scalar = std::is_floating_point_v<T>;
int main() {
  double values[2] = {1, 2};
  return Scalar<double> && std::span<double>(values).size() == 2 ? 0 : 1;
}
]=])
run(EXPECT ok COMMAND c++ -std=c++20 "${WORK}/cxx20_user.cpp" ${flags} -pthread
                      -o "${WORK}/cxx20_user")
run(EXPECT ok COMMAND "${WORK}/cxx20_user")
if(rasterizer)
  run(EXPECT ok OUTPUT raster_flags COMMAND ${PKG_CONFIG} --cflags --libs oblique-testing-raster gtest_main)
  string(STRIP "${raster_flags}" raster_flags)
  separate_arguments(raster_flags UNIX_COMMAND "${raster_flags}")
  run(EXPECT ok COMMAND c++ -O1 -DENGINE_FIXED=1 "${SOURCE}/examples/downstream/engine_raster_test.cpp"
                        "${SOURCE}/examples/downstream/engine.cpp" ${raster_flags} -pthread
                        -o "${WORK}/engine_raster_test_pkg_config")
  run(EXPECT ok COMMAND "${WORK}/engine_raster_test_pkg_config")
endif()
run(EXPECT ok OUTPUT version COMMAND "${prefix}/bin/oblique" --version)
if(NOT version MATCHES "^oblique [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit [^)]+\\)")
  message(FATAL_ERROR "the installed bin/oblique --version said: ${version}")
endif()
message(STATUS "pkg-config builds the test (${flags}); ${version}")

if(CLANGXX)
  run(EXPECT ok COMMAND ${CMAKE_COMMAND} -S "${SOURCE}/examples/downstream" -B "${WORK}/clang"
                        -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_CXX_COMPILER=${CLANGXX})
  run(EXPECT ok COMMAND ${CMAKE_COMMAND} --build "${WORK}/clang" --target engine_fuzz)
  file(MAKE_DIRECTORY "${WORK}/new-inputs")
  run(EXPECT fail OUTPUT output DIR "${WORK}"
      COMMAND "${WORK}/clang/engine_fuzz" -runs=100000 -artifact_prefix=${WORK}/
              -dict=${prefix}/share/oblique/fuzz/oblique.dict "${WORK}/new-inputs"
              "${prefix}/share/oblique/fuzz/corpus")
  if(NOT output MATCHES "oblique property violated: [a-z_]+ by make_oblique")
    message(FATAL_ERROR "the libFuzzer target did not catch make_oblique:\n${output}")
  endif()
  message(STATUS "the libFuzzer target (${CLANGXX}) builds and catches make_oblique")
endif()
