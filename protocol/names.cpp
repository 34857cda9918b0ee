#include "oblique/protocol/names.h"

#include <algorithm>
#include <cctype>

namespace oblique::protocol {

namespace {

/// Optimal string alignment distance: insertions, deletions, substitutions and swaps of two
/// neighbouring letters each cost 1; letters compared without case.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  auto same = [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  };
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = same(a[i - 1], b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

}  // namespace

std::string closest_name(std::string_view name, const std::vector<std::string>& known) {
  if (name.empty() || name.size() > 64) return "";
  std::string best;
  std::size_t best_distance = 0;
  for (const std::string& k : known) {
    const std::size_t limit = std::min<std::size_t>(3, std::max(name.size(), k.size()) / 3);
    const std::size_t distance = edit_distance(name, k);
    if (distance <= limit && (best.empty() || distance < best_distance)) {
      best = k;
      best_distance = distance;
    }
  }
  if (!best.empty()) return best;
  std::vector<std::string> prefixed;
  for (const std::string& k : known) {
    if (k.size() > name.size() && k.compare(0, name.size(), name) == 0) prefixed.push_back(k);
  }
  return prefixed.size() == 1 ? prefixed.front() : "";
}

std::string name_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string unknown_name(std::string_view what, std::string_view name,
                         const std::vector<std::string>& known) {
  std::string out = "unknown " + std::string(what) + " \"" + std::string(name) + "\" (";
  if (const std::string guess = closest_name(name, known); !guess.empty())
    out += "did you mean " + guess + "?; ";
  return out + "known: " + name_list(known) + ")";
}

}  // namespace oblique::protocol
