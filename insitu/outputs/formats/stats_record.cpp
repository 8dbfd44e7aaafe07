#include "insitu/outputs/formats/stats_record.h"

#include "insitu/outputs/formats/json_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace voxspan {
namespace {

template <class T>
T* find_named(std::vector<std::pair<std::string, T>>& items, std::string_view name) {
  for (auto& [n, v] : items)
    if (n == name) return &v;
  return nullptr;
}

template <class T>
void append_object(std::string& out, std::string_view key,
                   const std::vector<std::pair<std::string, T>>& items) {
  append_string(out, key);
  out += ":{";
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += ',';
    append_string(out, items[i].first);
    out += ':';
    append_number(out, items[i].second);
  }
  out += '}';
}

// "<key>":{"<pass>":ms,...}
void append_timings(std::string& out, std::string_view key, const FrameStats& s) {
  append_string(out, key);
  out += ":{";
  for (std::size_t i = 0; i < s.passes.size(); ++i) {
    if (i) out += ',';
    append_string(out, s.passes[i].name);
    out += ':';
    append_number(out, s.passes[i].ms);
  }
  out += '}';
}

void append_section(std::string& out, const FrameStats& s) {
  append_timings(out, "timings_ms", s);
  out += ',';
  append_object(out, "counters", s.counts);
}

void append_ranks(std::string& out, const StatsRecord::Ranks& ranks) {
  out += ",\"ranks\":{\"count\":";
  append_number(out, std::int64_t(ranks.count));
  out += ",\"bytes_sent\":[";
  for (std::size_t i = 0; i < ranks.bytes_sent.size(); ++i) {
    if (i) out += ',';
    append_number(out, ranks.bytes_sent[i]);
  }
  out += "],";
  append_timings(out, "timings_ms_mean", ranks.totals_mean);
  out += ",\"views\":{";
  for (std::size_t i = 0; i < ranks.views_mean.size(); ++i) {
    if (i) out += ',';
    append_string(out, ranks.views_mean[i].first);
    out += ":{";
    append_timings(out, "timings_ms_mean", ranks.views_mean[i].second);
    out += '}';
  }
  out += "}}";
}

}  // namespace

FrameStats& StatsRecord::view(std::string_view name) {
  if (FrameStats* s = find_named(views, name)) return *s;
  views.emplace_back(std::string(name), FrameStats{});
  return views.back().second;
}

void StatsRecord::set_memory(std::string_view name, double mib) {
  if (double* v = find_named(memory_mib, name)) *v = mib;
  else memory_mib.emplace_back(std::string(name), mib);
}

void StatsRecord::clear() {
  step = 0;
  time = 0;
  totals.clear();
  for (auto& [name, section] : views) section.clear();
  memory_mib.clear();
  error.clear();
}

void StatsRecord::zero() {
  step = 0;
  time = 0;
  totals.zero();
  for (auto& entry : views) entry.second.zero();
  for (auto& entry : memory_mib) entry.second = 0;
  error.clear();
}

std::string to_json_line(const StatsRecord& r) {
  std::string out;
  out.reserve(256);
  append_json_line(r, out);
  return out;
}

void append_json_line(const StatsRecord& r, std::string& out) {
  out += "{\"step\":";
  append_number(out, r.step);
  out += ",\"time\":";
  append_number(out, r.time);
  out += ',';
  append_section(out, r.totals);
  out += ',';
  append_object(out, "memory_mib", r.memory_mib);
  out += ",\"views\":{";
  bool first = true;
  for (const auto& [name, section] : r.views) {
    if (!first) out += ',';
    first = false;
    append_string(out, name);
    out += ":{";
    append_section(out, section);
    out += '}';
  }
  out += '}';
  if (r.ranks.count > 1) append_ranks(out, r.ranks);
  if (!r.error.empty()) {
    out += ",\"error\":";
    append_string(out, r.error);
  }
  out += "}\n";
}

}  // namespace voxspan
