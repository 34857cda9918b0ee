// The engine idioms (idioms.txt, docs/engines.md) through oblique::testing, as an engine's own
// property test declares its function: adapted in its storage (a row-vector engine with
// Layout::row_vectors) and convention, under the engine contract narrowed to the families it
// claims. One test per line of idioms.txt: RightMatrices.NAME passes; WrongMatrices.NAME (CTest
// runs one at a time) is caught and its report names what idioms.txt says. UndeclaredLayout:
// the Direct3D-style function declared as M by rows, named transposed_layout.
// OBLIQUE_ENGINE_MATRICES is this folder.
#include <gtest/gtest.h>
#include <oblique/testing.h>

#include "idiom_claims.h"

namespace {

class Idiom : public ::testing::Test {
 public:
  Idiom(engine_matrices::Claims claims, bool wrong) : claims_(std::move(claims)), wrong_(wrong) {}
  void TestBody() override {
    oblique::testing::check_properties(engine_matrices::implementation(claims_, wrong_),
                                       claims_.contract);
  }

 private:
  engine_matrices::Claims claims_;
  bool wrong_;
};

const bool registered = [] {
  for (const engine_matrices::Claims& c :
       engine_matrices::read_claims(std::string(OBLIQUE_ENGINE_MATRICES) + "/idioms.txt")) {
    for (const bool wrong : {false, true}) {
      ::testing::RegisterTest(wrong ? "WrongMatrices" : "RightMatrices", c.name.c_str(), nullptr,
                              nullptr, __FILE__, __LINE__,
                              [c, wrong]() -> ::testing::Test* { return new Idiom(c, wrong); });
    }
  }
  return true;
}();

}  // namespace

// The Direct3D-style function declared without its layout (Layout::row_major, M by rows): it
// reads M as its R and writes its oblique row into M's third column.
TEST(UndeclaredLayout, d3d_left_handed) {
  oblique::Contract claims = oblique::engine_contract();
  claims.conventions = {oblique::Convention::zero_one};
  claims.families = {oblique::cases::Family::left_handed,
                     oblique::cases::Family::left_handed_x_flipped};
  oblique::testing::check_properties(
      oblique::adapt<float>("d3d_left_handed_as_row_major", oblique::Layout::row_major,
                            oblique::Convention::zero_one,
                            engine_matrices::find("d3d_left_handed", nullptr)->right),
      claims);
}
