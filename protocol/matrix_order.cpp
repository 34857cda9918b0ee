// other_matrix_order(): a scan of a JSON line's arrays, each flat one of 16 elements transposed.
#include "oblique/protocol/matrix_order.h"

#include <cstddef>
#include <vector>

namespace oblique::protocol {

std::optional<MatrixOrder> matrix_order_of_layout(std::string_view name) {
  if (name == "row_major") return MatrixOrder::rows;
  if (name == "column_major" || name == "row_vectors") return MatrixOrder::columns;
  return std::nullopt;
}

namespace {

/// The end of the JSON string starting at `at` (its opening quote): the index past its closing
/// quote, or the line's size when it does not close.
std::size_t string_end(std::string_view line, std::size_t at) {
  for (std::size_t i = at + 1; i < line.size(); ++i) {
    if (line[i] == '\\') {
      ++i;
    } else if (line[i] == '"') {
      return i + 1;
    }
  }
  return line.size();
}

}  // namespace

std::string other_matrix_order(std::string_view line) {
  std::string out(line);
  // Each open array: where it starts, the spans of its elements so far, whether one of them is
  // an array or an object (then it is no matrix). A stack, not recursion: a hostile line's depth
  // costs memory in proportion to its length, never the call stack.
  struct Open {
    std::size_t element_start;
    std::vector<std::pair<std::size_t, std::size_t>> elements;
    bool nested = false;
  };
  std::vector<Open> open;
  std::ptrdiff_t shift = 0;  // out.size() - line.size() so far
  auto end_element = [&](std::size_t at) {
    Open& a = open.back();
    std::size_t b = a.element_start, e = at;
    auto blank = [](char x) { return x == ' ' || x == '\t' || x == '\r' || x == '\n'; };
    while (b < e && blank(line[b])) ++b;
    while (e > b && blank(line[e - 1])) --e;
    if (e > b) a.elements.emplace_back(b, e);
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      i = string_end(line, i) - 1;
    } else if (c == '[' || c == '{') {
      if (!open.empty()) open.back().nested = true;
      if (c == '[')
        open.push_back(Open{i + 1, {}, false});
      else
        open.push_back(Open{i + 1, {}, true});  // an object: its members are not elements
    } else if (c == ',' && !open.empty()) {
      end_element(i);
      open.back().element_start = i + 1;
    } else if ((c == ']' || c == '}') && !open.empty()) {
      end_element(i);
      const Open a = open.back();
      open.pop_back();
      if (c != ']' || a.nested || a.elements.size() != 16) continue;
      // Transposed: the element at (r, c) goes to (c, r); each element's text moves whole.
      std::string body;
      for (int k = 0; k < 16; ++k) {
        const auto [b, e] = a.elements[static_cast<std::size_t>(4 * (k % 4) + k / 4)];
        if (k) body += ", ";
        body += line.substr(b, e - b);
      }
      // Spliced into `out` where the elements stood: every earlier splice was of an array that
      // ended before this one began (a matrix holds no array), so `shift` is what they changed.
      const std::size_t start = a.elements.front().first, stop = a.elements.back().second;
      out.replace(static_cast<std::size_t>(static_cast<std::ptrdiff_t>(start) + shift),
                  stop - start, body);
      shift += static_cast<std::ptrdiff_t>(body.size()) - static_cast<std::ptrdiff_t>(stop - start);
    }
  }
  return out;
}

}  // namespace oblique::protocol
