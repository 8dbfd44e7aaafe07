// render/frame_stats.h - what one render step did: milliseconds per pass, named counts (culled
// particles, spans, capped pixels...), named figures (layer spacing...) and GPU memory. Every
// pass of either renderer reports into it through a Recorder (render/recorder.h), so the
// runtime writes one record per step whatever the passes were. Plain data.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace voxspan {

struct FrameStats {
  struct Pass {
    std::string name;
    double ms = 0;  // summed over runs (a pass runs once per tile)
    int runs = 0;
  };
  std::vector<Pass> passes;                                  // in order of first run
  std::vector<std::pair<std::string, std::int64_t>> counts;  // in order of first report
  std::vector<std::pair<std::string, double>> figures;       // in order of first report
  std::int64_t gpu_bytes = 0;       // held by GL buffers and textures when collected
  std::int64_t gpu_peak_bytes = 0;  // most held at once since the step began

  void add_time(std::string_view pass, double ms);
  void add_count(std::string_view name, std::int64_t value);
  void set_count(std::string_view name, std::int64_t value);
  void set_figure(std::string_view name, double value);

  // 0 when the pass did not run or the name was never reported.
  double ms(std::string_view pass) const;
  int runs(std::string_view pass) const;
  std::int64_t count(std::string_view name) const;
  double figure(std::string_view name) const;
  bool has_count(std::string_view name) const;
  double total_ms() const;

  // One JSON object on one line: {"passes":{"splat":{"ms":..,"runs":..},..},"counts":{..},
  // "figures":{..},"gpu_bytes":..,"gpu_peak_bytes":..}.
  std::string json() const;
  void clear();
  // Every value to 0, every name kept: a FrameStats refilled each step allocates nothing.
  void zero();
  bool empty() const { return passes.empty() && counts.empty() && figures.empty(); }
};

}  // namespace voxspan
