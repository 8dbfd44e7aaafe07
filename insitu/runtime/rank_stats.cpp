#include "insitu/runtime/rank_stats.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "voxspan/error.h"

namespace voxspan {
namespace {

// A record's sections as bytes: per section its name, then its passes (name, ms) and counts
// (name, value). Names are length-prefixed.
class Writer {
 public:
  template <class T> void value(const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof v);
  }
  void text(const std::string& s) {
    value(std::uint32_t(s.size()));
    const auto* p = reinterpret_cast<const std::byte*>(s.data());
    bytes.insert(bytes.end(), p, p + s.size());
  }
  void section(const std::string& name, const FrameStats& s) {
    text(name);
    value(std::uint32_t(s.passes.size()));
    for (const FrameStats::Pass& p : s.passes) text(p.name), value(p.ms);
    value(std::uint32_t(s.counts.size()));
    for (const auto& [n, v] : s.counts) text(n), value(v);
  }
  std::vector<std::byte> bytes;
};

class Reader {
 public:
  explicit Reader(const std::vector<std::byte>& bytes) : bytes_(bytes) {}
  bool done() const { return at_ == bytes_.size(); }
  template <class T> T value() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  std::string text() {
    std::string s(value<std::uint32_t>(), '\0');
    take(s.data(), s.size());
    return s;
  }
  // Adds the section into `into` (named `name` on return).
  void section(std::string& name, FrameStats& into) {
    name = text();
    for (std::uint32_t n = value<std::uint32_t>(); n > 0; --n) {
      const std::string pass = text();
      into.add_time(pass, value<double>());
    }
    for (std::uint32_t n = value<std::uint32_t>(); n > 0; --n) {
      const std::string count = text();
      into.add_count(count, value<std::int64_t>());
    }
  }

 private:
  void take(void* out, std::size_t n) {
    if (bytes_.size() - at_ < n) throw make_error("a rank's stats record is cut short");
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::vector<std::byte>& bytes_;
  std::size_t at_ = 0;
};

// Per pass the slowest rank's time into `slowest` and the mean into `mean`; counts summed.
struct Combined {
  FrameStats sum, slowest;
};

void fold(const FrameStats& rank, Combined& c) {
  for (const FrameStats::Pass& p : rank.passes) {
    c.sum.add_time(p.name, p.ms);
    bool found = false;
    for (FrameStats::Pass& q : c.slowest.passes)
      if (q.name == p.name) q.ms = std::max(q.ms, p.ms), found = true;
    if (!found) c.slowest.add_time(p.name, p.ms);
  }
  for (const auto& [n, v] : rank.counts) c.slowest.add_count(n, v);
}

FrameStats mean_of(const FrameStats& sum, int ranks) {
  FrameStats mean;
  for (const FrameStats::Pass& p : sum.passes) mean.add_time(p.name, p.ms / ranks);
  return mean;
}

}  // namespace

void combine_rank_records(Communicator& comm, std::int64_t bytes_sent, StatsRecord& record) {
  Writer w;
  w.value(bytes_sent);
  w.section("", record.totals);
  for (const auto& [name, view] : record.views) w.section(name, view);
  const std::vector<std::vector<std::byte>> all = comm.gather(w.bytes);
  if (!comm.root()) return;
  StatsRecord::Ranks& ranks = record.ranks;
  ranks.count = comm.size();
  ranks.bytes_sent.clear();
  Combined totals;
  std::vector<std::pair<std::string, Combined>> views;
  for (const std::vector<std::byte>& bytes : all) {
    Reader r(bytes);
    ranks.bytes_sent.push_back(r.value<std::int64_t>());
    std::string name;
    FrameStats section;
    r.section(name, section);
    fold(section, totals);
    while (!r.done()) {
      section = FrameStats{};
      r.section(name, section);
      auto it = std::find_if(views.begin(), views.end(), [&](auto& v) { return v.first == name; });
      if (it == views.end()) it = views.insert(views.end(), {name, Combined{}});
      fold(section, it->second);
    }
  }
  record.totals.passes = totals.slowest.passes;
  record.totals.counts = totals.slowest.counts;
  ranks.totals_mean = mean_of(totals.sum, comm.size());
  ranks.views_mean.clear();
  for (auto& [name, c] : views) {
    FrameStats& v = record.view(name);
    v.passes = c.slowest.passes;
    v.counts = c.slowest.counts;
    ranks.views_mean.emplace_back(name, mean_of(c.sum, comm.size()));
  }
}

}  // namespace voxspan
