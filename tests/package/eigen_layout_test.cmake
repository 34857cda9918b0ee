# A file built with other SIMD flags than the libraries cannot link against their interfaces that
# take structs holding Eigen matrices (oblique/util/eigen_layout.h): compiled as is and with
# -mavx2, a file calling oblique::fuzzing::test_one_input, oracle::Checker and the case
# builder refers to them in eigen_align16 and in eigen_align32; the libraries define the first
# (the one of their own build) and not the second. Usage: cmake -DCXX=... -DSOURCE=<repository>
#   -DFUZZING=<lib> -DPROPERTIES=<the oracle library, which holds the checker>
#   -DCASES=<the cases library, which holds the case builder> -DEIGEN=<include dir> -DWORK=<dir>
#   -P eigen_layout_test.cmake
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/uses_libraries.cpp [=[
#include <oblique/cases/case_builder.h>
#include <oblique/fuzzing.h>
#include <oblique/oracle/checker.h>
void make_oblique(float m[16], const float plane[4]);
int fuzz_one(const std::uint8_t* data, std::size_t size) {
  static const auto mine =
      oblique::adapt<float>("make_oblique", oblique::Layout::column_major, oblique::Convention::gl, make_oblique);
  return oblique::fuzzing::test_one_input(data, size, mine);
}
bool holds(const oblique::Matrix4<float>& m, const oblique::Vector4<float>& c) {
  return oblique::oracle::Checker<float>(m, c, oblique::Convention::gl)
      .judge(oblique::Answer<float>{oblique::Status::ok, m})
      .holds();
}
oblique::cases::Case<float> built() {
  using namespace oblique::cases;
  return build_case<float>(Family::perspective, oblique::Convention::gl, Place::typical, 0,
                           [](int lo, int) { return lo; });
}
]=])
set(includes -I${SOURCE}/core/include -I${SOURCE}/protocol/include -I${SOURCE}/cases/include -I${SOURCE}/oracle/include
    -I${SOURCE}/mistakes/include -I${SOURCE}/run/include -I${SOURCE}/report/include
    -I${SOURCE}/fuzzing/include -isystem ${EIGEN})

function(symbols file out)  # the demangled names nm lists for `file`
  execute_process(COMMAND nm -C ${file} OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "nm ${file} failed")
  endif()
  set(${out} "${listing}" PARENT_SCOPE)
endfunction()

foreach(variant baseline avx2)
  set(flags -std=c++17 -O1)
  if(variant STREQUAL avx2)
    list(APPEND flags -mavx2)
  endif()
  execute_process(COMMAND ${CXX} ${flags} ${includes} -c ${WORK}/uses_libraries.cpp
                          -o ${WORK}/${variant}.o RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "compiling with ${flags} failed:\n${err}")
  endif()
  symbols(${WORK}/${variant}.o ${variant}_symbols)
endforeach()
symbols(${FUZZING} fuzzing_symbols)
symbols(${PROPERTIES} properties_symbols)
symbols(${CASES} cases_symbols)

set(failures "")
function(expect_in listing text what)  # `text` occurs in `listing` (or, with what = "no ...", not)
  string(FIND "${listing}" "${text}" at)
  if(what MATCHES "^no " AND NOT at EQUAL -1)
    set(failures "${failures}  ${what}: found ${text}\n" PARENT_SCOPE)
  elseif(NOT what MATCHES "^no " AND at EQUAL -1)
    set(failures "${failures}  ${what}: no ${text}\n" PARENT_SCOPE)
  endif()
endfunction()
expect_in("${baseline_symbols}" "U int oblique::fuzzing::eigen_align16::test_one_input<float>("
          "the baseline file refers to test_one_input in eigen_align16")
expect_in("${baseline_symbols}" "U oblique::oracle::eigen_align16::Checker<float>::judge("
          "the baseline file refers to Checker::judge in eigen_align16")
expect_in("${avx2_symbols}" "U int oblique::fuzzing::eigen_align32::test_one_input<float>("
          "the -mavx2 file refers to test_one_input in eigen_align32")
expect_in("${avx2_symbols}" "U oblique::oracle::eigen_align32::Checker<float>::judge("
          "the -mavx2 file refers to Checker::judge in eigen_align32")
expect_in("${fuzzing_symbols}" "W int oblique::fuzzing::eigen_align16::test_one_input<float>("
          "oblique::fuzzing defines test_one_input in eigen_align16")
expect_in("${fuzzing_symbols}" "eigen_align32" "no eigen_align32 in oblique::fuzzing")
expect_in("${properties_symbols}" "W oblique::oracle::eigen_align16::Checker<float>::judge("
          "oblique::properties defines Checker::judge in eigen_align16")
expect_in("${properties_symbols}" "eigen_align32" "no eigen_align32 in oblique::properties")
expect_in("${baseline_symbols}" "U oblique::cases::Case<float> oblique::cases::eigen_align16::build_case<float>("
          "the baseline file refers to build_case in eigen_align16")
expect_in("${avx2_symbols}" "U oblique::cases::Case<float> oblique::cases::eigen_align32::build_case<float>("
          "the -mavx2 file refers to build_case in eigen_align32")
expect_in("${cases_symbols}" "W oblique::cases::Case<float> oblique::cases::eigen_align16::build_case<float>("
          "oblique::cases defines build_case in eigen_align16")
expect_in("${cases_symbols}" "eigen_align32" "no eigen_align32 in oblique::cases")
if(failures)
  message(FATAL_ERROR "Eigen's layout in the interfaces' names:\n${failures}")
endif()
message(STATUS "a -mavx2 file names eigen_align32, which the libraries do not define")
