// An engine idiom (engine_matrices.h) served over the apply protocol, as an engine's adapter for
// `oblique verify --impl` and `oblique check --impl` would serve it: the request's matrix (by
// rows, M acting on column vectors) is put in the idiom's storage (column-major, or a row-vector
// engine's R = M^T by rows: the same 16 numbers), the idiom runs in float, and its answer is read
// back from that storage. With --as-stored the adapter moves nothing: the 16 numbers of the
// request are the idiom's storage as they come, and its answer is written so (the caller says
// `--layout column_major` or `row_vectors`). The idiom serves one convention; the caller says
// which (--convention).
//
// Usage: example_engine_matrices NAME [--as-stored]   (NAME from idioms.txt; NAME_wrong for its
//        twin)
#include <cstdio>
#include <iostream>
#include <string>

#include "engine_matrices.h"
#include "oblique/protocol/protocol.h"

namespace {

namespace protocol = oblique::protocol;
using oblique::Status;

std::string answer(engine_matrices::Function function, bool as_stored, const std::string& line) {
  const oblique::Expected<protocol::Request> request = protocol::parse_request(line);
  if (!request) return protocol::refusal_line(Status::invalid_input, request.error());
  float numbers[16], plane[4];
  for (int i = 0; i < 16; ++i) {
    const oblique::Expected<float> v = protocol::parse_number<float>(request->projection[i]);
    if (!v) return protocol::refusal_line(Status::invalid_input, v.error());
    // M(r, c) = request[4 r + c] at 4 c + r; as stored, where it stands
    numbers[as_stored ? i : 4 * (i % 4) + i / 4] = *v;
  }
  for (int i = 0; i < 4; ++i) {
    const oblique::Expected<float> v = protocol::parse_number<float>(request->plane[i]);
    if (!v) return protocol::refusal_line(Status::invalid_input, v.error());
    plane[i] = *v;
  }
  function(numbers, plane);
  oblique::Matrix4<float> out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out(r, c) = numbers[as_stored ? 4 * r + c : 4 * c + r];
  }
  return protocol::ok_answer_line(out);
}

}  // namespace

int main(int argc, char** argv) {
  bool wrong = false;
  const engine_matrices::Idiom* idiom = argc > 1 ? engine_matrices::find(argv[1], &wrong) : nullptr;
  if (!idiom) {
    std::fprintf(
        stderr,
        "usage: %s NAME [--as-stored]: no idiom '%s' (examples/engine_matrices/idioms.txt)\n",
        argv[0], argc > 1 ? argv[1] : "");
    return 2;
  }
  const engine_matrices::Function function = wrong ? idiom->wrong : idiom->right;
  const bool as_stored = argc > 2 && std::string(argv[2]) == "--as-stored";
  std::string line;
  while (std::getline(std::cin, line)) {
    std::cout << answer(function, as_stored, line) << std::endl;
    if (!std::cout) {  // a closed pipe, a full disk: said, not answered into nothing
      std::fprintf(stderr, "%s: cannot write the answer\n", argv[0]);
      return 1;
    }
  }
  return 0;
}
