#include "render/volume_parts.h"

#include <algorithm>

namespace voxspan {

void shared_ranges(std::span<const SampleRange> hulls,
                   std::vector<std::vector<SampleRange>>& shared) {
  // The samples two or more hulls hold: a sweep over the hulls' ends.
  std::vector<std::pair<std::int64_t, int>> ends;  // (sample, +1 at a first, -1 after a last)
  for (const SampleRange& h : hulls)
    if (!h.empty()) {
      ends.push_back({h.first, 1});
      ends.push_back({std::int64_t(h.last) + 1, -1});
    }
  std::sort(ends.begin(), ends.end());
  std::vector<SampleRange> twice;
  int depth = 0;
  std::int64_t since = 0;
  for (std::size_t k = 0; k < ends.size();) {
    const std::int64_t at = ends[k].first;
    const int before = depth;
    for (; k < ends.size() && ends[k].first == at; ++k) depth += ends[k].second;
    if (before < 2 && depth >= 2) since = at;
    if (before >= 2 && depth < 2) twice.push_back({std::int32_t(since), std::int32_t(at - 1)});
  }
  for (std::size_t r = 0; r < hulls.size(); ++r)
    for (const SampleRange& t : twice) {
      const SampleRange cut{std::max(t.first, hulls[r].first), std::min(t.last, hulls[r].last)};
      if (!cut.empty()) shared[r].push_back(cut);
    }
}

}  // namespace voxspan
