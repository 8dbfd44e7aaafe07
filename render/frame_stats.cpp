#include "render/frame_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace voxspan {
namespace {

template <class T> auto find_named(T& list, std::string_view name) {
  return std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == name; });
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// Names are ours (pass and counter names), never user text: no escaping needed beyond quotes.
std::string quoted(std::string_view s) {
  std::string q;
  q.reserve(s.size() + 2);
  q += '"';
  q.append(s);
  q += '"';
  return q;
}

}  // namespace

void FrameStats::add_time(std::string_view pass, double ms) {
  auto it =
      std::find_if(passes.begin(), passes.end(), [&](const Pass& p) { return p.name == pass; });
  if (it == passes.end()) it = passes.insert(passes.end(), Pass{std::string(pass), 0, 0});
  it->ms += ms;
  ++it->runs;
}

void FrameStats::add_count(std::string_view name, std::int64_t value) {
  auto it = find_named(counts, name);
  if (it == counts.end()) counts.emplace_back(std::string(name), value);
  else it->second += value;
}

void FrameStats::set_count(std::string_view name, std::int64_t value) {
  auto it = find_named(counts, name);
  if (it == counts.end()) counts.emplace_back(std::string(name), value);
  else it->second = value;
}

void FrameStats::set_figure(std::string_view name, double value) {
  auto it = find_named(figures, name);
  if (it == figures.end()) figures.emplace_back(std::string(name), value);
  else it->second = value;
}

double FrameStats::ms(std::string_view pass) const {
  for (const Pass& p : passes)
    if (p.name == pass) return p.ms;
  return 0;
}

int FrameStats::runs(std::string_view pass) const {
  for (const Pass& p : passes)
    if (p.name == pass) return p.runs;
  return 0;
}

std::int64_t FrameStats::count(std::string_view name) const {
  auto it = find_named(counts, name);
  return it == counts.end() ? 0 : it->second;
}

bool FrameStats::has_count(std::string_view name) const {
  return find_named(counts, name) != counts.end();
}

double FrameStats::figure(std::string_view name) const {
  auto it = find_named(figures, name);
  return it == figures.end() ? 0.0 : it->second;
}

double FrameStats::total_ms() const {
  double total = 0;
  for (const Pass& p : passes) total += p.ms;
  return total;
}

std::string FrameStats::json() const {
  std::ostringstream out;
  out << "{\"passes\":{";
  for (std::size_t i = 0; i < passes.size(); ++i)
    out << (i ? "," : "") << quoted(passes[i].name) << ":{\"ms\":" << json_number(passes[i].ms)
        << ",\"runs\":" << passes[i].runs << "}";
  out << "},\"counts\":{";
  for (std::size_t i = 0; i < counts.size(); ++i)
    out << (i ? "," : "") << quoted(counts[i].first) << ":" << counts[i].second;
  out << "},\"figures\":{";
  for (std::size_t i = 0; i < figures.size(); ++i)
    out << (i ? "," : "") << quoted(figures[i].first) << ":" << json_number(figures[i].second);
  out << "},\"gpu_bytes\":" << gpu_bytes << ",\"gpu_peak_bytes\":" << gpu_peak_bytes << "}";
  return out.str();
}

void FrameStats::clear() { *this = FrameStats{}; }

void FrameStats::zero() {
  for (Pass& p : passes) p.ms = 0, p.runs = 0;
  for (auto& entry : counts) entry.second = 0;
  for (auto& entry : figures) entry.second = 0;
  gpu_bytes = 0;
  gpu_peak_bytes = 0;
}

}  // namespace voxspan
