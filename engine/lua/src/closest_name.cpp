// Suggestions for mistyped names (closest_name.h).
#include "rigidlab/lua/closest_name.h"

#include <algorithm>
#include <cctype>
#include <cstdint>

namespace rigidlab::lua {

std::string closestName(std::string_view name, const std::vector<std::string_view>& candidates, Closeness rule) {
  // Optimal string alignment distance: Levenshtein plus swaps of two neighbouring letters.
  const auto distance = [](std::string_view a, std::string_view b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
      for (size_t j = 1; j <= b.size(); ++j) {
        d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
        if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    return d[a.size()][b.size()];
  };
  const auto lower = [](std::string_view s) {
    std::string l(s);
    for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return l;
  };
  if (name.size() < rule.min_length || name.size() > 64) return "";
  std::string best;
  size_t best_distance = SIZE_MAX;
  for (std::string_view c : candidates) {
    size_t d = distance(name, c);
    const size_t allowed = std::max(std::max(name.size(), c.size()) / 5, rule.min_edits);
    if (lower(name) == lower(c)) d = 0;
    else if (c.starts_with(name)) d = std::min(d, allowed);  // a name cut short: always a candidate
    else if (d > allowed) continue;
    if (d < best_distance) {
      best_distance = d;
      best = std::string(c);
    }
  }
  return best;
}

}  // namespace rigidlab::lua
