#include "near_name.h"

#include <algorithm>
#include <vector>

namespace voxspan {
namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string near_name(std::string_view name, std::span<const std::string_view> known) {
  std::string best;
  std::size_t best_distance = 3;  // suggest only near misses
  for (std::string_view candidate : known) {
    const std::size_t d = edit_distance(name, candidate);
    if (d < best_distance) best_distance = d, best = std::string(candidate);
  }
  return best;
}

std::string attributes_instead(const ParticleView& particles, std::string_view name) {
  if (particles.attribute_count() == 0) return "it passes none";
  std::vector<std::string_view> passed;
  std::string text = "it passes: ";
  for (int k = 0; k < particles.attribute_count(); ++k) {
    passed.push_back(particles.attribute(k).name);
    text.append(k == 0 ? "" : ", ").append(passed.back());
  }
  const std::string near = near_name(name, passed);
  return near.empty() ? text : "did you mean \"" + near + "\"? " + text;
}

}  // namespace voxspan
