// The engine idioms (idioms.txt) through the fuzz driver, each input judged for every right idiom
// under its claims (the driver decodes the input once per idiom, in its convention and
// families); OBLIQUE_IDIOM=NAME (or NAME_wrong) runs that one alone. With fuzzing_replay: files,
// or `--random N --seed S` mutated corpus inputs (replay_main.cpp).
#include <oblique/fuzzing.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "idiom_claims.h"

namespace {

struct Target {
  oblique::oracle::Implementation<float> impl;
  oblique::Contract contract;
};

std::vector<Target> targets() {
  const char* only = std::getenv("OBLIQUE_IDIOM");
  std::vector<Target> out;
  for (const engine_matrices::Claims& c :
       engine_matrices::read_claims(std::string(OBLIQUE_ENGINE_MATRICES) + "/idioms.txt")) {
    for (const bool wrong : {false, true}) {
      const std::string name = c.name + (wrong ? "_wrong" : "");
      if (only ? name == only : !wrong)
        out.push_back(Target{engine_matrices::implementation(c, wrong), c.contract});
    }
  }
  if (out.empty()) throw std::runtime_error("OBLIQUE_IDIOM names no idiom of idioms.txt");
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<Target> all = targets();
  for (const Target& t : all) oblique::fuzzing::test_one_input(data, size, t.impl, t.contract);
  return 0;
}
