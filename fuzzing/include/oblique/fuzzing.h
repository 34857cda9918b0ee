// The fuzz driver for your own function: the project's input decoder, and the exact judgement
// (oracle::judge). The decoder reads an input one of two ways (its fourth byte says which):
// as the picks of the case builder every way in shares (oblique/cases/case_builder.h), so the
// case is one of your contract's families, conventions and places as a property run draws them;
// or as numbers (a projection of a shape built from decoded parameters or 16 raw numbers, and a
// plane; every number a special value picked by index or 8 raw bytes), the hunt for extreme
// inputs, a family your contract does not claim left out. A libFuzzer target of a few lines:
//
//   #include <oblique/fuzzing.h>
//   void make_oblique(float m[16], const float plane[4]);   // yours
//
//   extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
//     static const auto mine = oblique::adapt<float>("make_oblique", oblique::Layout::column_major,
//                                                     oblique::Convention::gl, make_oblique);
//     return oblique::fuzzing::test_one_input(data, size, mine);
//   }
//
// Build it with clang++ -fsanitize=fuzzer,address and link oblique::fuzzing (the decoder and the
// exact checker are compiled there, for float, double and long double); run it on the seed
// corpus and with the dictionary installed in share/oblique/fuzz (oblique_FUZZ_DIR). A violation
// prints the case (decimal and hex), what the checker knows of it and the property broken, then
// aborts, which libFuzzer saves as a crash. Linking oblique::fuzzing_replay instead of
// -fsanitize=fuzzer gives a main() that replays files and directories, with any compiler.
// The decoder, the special values it picks and the case's judge: oblique/fuzzing/driver.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "oblique/cases/contract.h"
#include "oblique/depth_convention.h"
#include "oblique/oracle/adapter.h"
#include "oblique/oracle/consumers.h"
#include "oblique/util/eigen_layout.h"

namespace oblique::fuzzing {

/// The body of a libFuzzer target for one function: decodes the input (in the function's scalar
/// type, whatever the scalar byte says, in one of the contract's conventions), runs the function
/// and judges its answer under the contract (oblique/cases/contract.h: its conventions,
/// families, planes, statuses, refusals, properties and row3_accuracy: an input of a family the
/// contract does not claim is not given to the function, under unit planes the plane's normal is
/// scaled to length 1, and inputs without an answer are judged as the statuses say; the decoder
/// makes its own planes, so the contract's places are not chosen); aborts on a violation. Inputs
/// left out (by the contract, by `accepts`, or within rounding of no answer) are counted and
/// printed at exit with those judged. Returns 0,
/// as LLVMFuzzerTestOneInput does. Compiled in oblique::fuzzing for float, double and long double
/// (in a namespace named by Eigen's layout: oblique/util/eigen_layout.h).
inline namespace OBLIQUE_EIGEN_LAYOUT {
template <class T>
int test_one_input(const std::uint8_t* data, std::size_t size,
                   const oracle::Implementation<T>& impl, const Contract& contract = {});
/// The body of a libFuzzer target for the code around the matrix (oblique::Consumers, as
/// oblique::testing::check_consumers takes it): decodes M and C as test_one_input() does (in one
/// of the contract's conventions and families, unit planes scaled; `consumers.accepts` honoured
/// by consumer_round()), takes the core's oblique matrix for them, and with choices read
/// from the input's end (a point of the kept region, the depth buffer, a main view, a mirror's
/// plane, portal frames) asks each function given and judges its answer by its properties
/// (oblique/oracle/consumers.h). On a violation prints the finding and every input
/// (round-trip decimals), then aborts. Returns 0.
template <class T>
int test_consumers(const std::uint8_t* data, std::size_t size, const Consumers<T>& consumers,
                   const Contract& contract = {});
}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::fuzzing
