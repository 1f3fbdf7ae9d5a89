#include "cases/nearest_name.hpp"

#include <algorithm>
#include <vector>

namespace pb {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string_view nearest_name(std::string_view word, std::span<const std::string_view> names, std::size_t max_edits) {
  std::string_view best;
  std::size_t best_d = max_edits + 1;
  for (std::string_view name : names) {
    // A length apart of best_d or more is never closer: skip the quadratic distance (a
    // 10 MB key would take seconds).
    if ((word.size() > name.size() ? word.size() - name.size() : name.size() - word.size()) >= best_d) continue;
    const std::size_t d = edit_distance(word, name);
    if (d < best_d) best_d = d, best = name;
  }
  return best;
}

}  // namespace pb
