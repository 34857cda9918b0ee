// Any entry of the catalogue of known mistakes (mistakes/mistakes.h), or two together, served
// over the apply protocol: what `oblique verify` and its diagnosis see of an engine with that
// mistake. CTest runs verify on each entry and expects the report to name it.
//
// Usage: example_catalogue_mistake NAME[+NAME] [--float]
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "oblique/mistakes/mistakes.h"
#include "oblique/protocol/protocol.h"

namespace {

using oblique::Convention;
using oblique::Status;
namespace mistakes = oblique::mistakes;
namespace oracle = oblique::oracle;
namespace protocol = oblique::protocol;

template <class T>
std::string answer(const oracle::Implementation<T>& impl, const std::string& line) {
  const oblique::Expected<protocol::Request> request = protocol::parse_request(line);
  if (!request) return protocol::refusal_line(Status::invalid_input, request.error());
  oblique::Matrix4<T> m;
  oblique::Vector4<T> c;
  for (int i = 0; i < 16; ++i) {
    const oblique::Expected<T> v = protocol::parse_number<T>(request->projection[i]);
    if (!v) return protocol::refusal_line(Status::invalid_input, v.error());
    m(i / 4, i % 4) = *v;
  }
  for (int i = 0; i < 4; ++i) {
    const oblique::Expected<T> v = protocol::parse_number<T>(request->plane[i]);
    if (!v) return protocol::refusal_line(Status::invalid_input, v.error());
    c(i) = *v;
  }
  const oblique::Answer<T> out = impl.run(m, c, request->convention.value_or(Convention::gl));
  if (out.status != Status::ok) return protocol::refusal_line(out.status, "");
  return protocol::ok_answer_line(out.projection);
}

template <class T>
int serve(const std::vector<mistakes::Mistake>& mistakes) {
  const oracle::Implementation<T> impl = mistakes::mistaken_implementation<T>(mistakes);
  std::string line;
  while (std::getline(std::cin, line)) std::cout << answer(impl, line) << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<mistakes::Mistake> mistakes;
  const std::string names = argc > 1 ? argv[1] : "";
  for (std::size_t start = 0; start <= names.size();) {
    const std::size_t end = std::min(names.find('+', start), names.size());
    const auto mistake = mistakes::parse_mistake(names.substr(start, end - start));
    if (!mistake) {
      std::fprintf(stderr, "usage: %s NAME[+NAME] [--float]: no mistake '%s' in the catalogue\n",
                   argv[0], names.substr(start, end - start).c_str());
      return 2;
    }
    mistakes.push_back(*mistake);
    start = end + 1;
  }
  const bool in_float = argc > 2 && std::strcmp(argv[2], "--float") == 0;
  return in_float ? serve<float>(mistakes) : serve<double>(mistakes);
}
