// render/recorder.h - the one way every pass of either renderer, and of the views around them,
// is timed and counted. A pass opens a Scope while it works; counters and figures go straight
// into the frame's FrameStats; collect() adds the finished scopes' milliseconds there.
//   host(pass):   work done on this thread or its thread pool: the wall clock;
//   device(pass): work issued to a device. Here the wall clock as well (the CPU renderer's
//                 passes are host work); the GL renderer's recorder (render/gl/gpu_recorder.h)
//                 times its scopes with GPU timer queries, or glFinish around them on llvmpipe.
// Names are StatName constants, each written once where its pass or counter lives
// (render/stat_names.h for a frame's), so that a record, a benchmark and a test read the same.
// Host scopes may sit inside anything; device scopes of the GL recorder must not nest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "render/frame_stats.h"
#include "voxspan/stopwatch.h"

namespace voxspan {

// The name of a pass, counter or figure. Constructed only explicitly, so that a call site
// names a constant instead of writing the text again.
struct StatName {
  std::string_view text;
  constexpr explicit StatName(std::string_view t) : text(t) {}
  constexpr operator std::string_view() const { return text; }  // NOLINT: FrameStats reads it
};

class Recorder {
 public:
  // Records into `stats` until record_into() names another; with none, into a FrameStats of
  // its own.
  explicit Recorder(FrameStats& stats) : stats_(&stats) {}
  Recorder() : stats_(&own_) {}
  virtual ~Recorder() = default;
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  class [[nodiscard]] Scope {
   public:
    ~Scope();
    Scope(Scope&& o) noexcept;
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    Scope& operator=(Scope&&) = delete;

   private:
    friend class Recorder;
    Scope(Recorder* recorder, std::size_t record) : recorder_(recorder), record_(record) {}
    Recorder* recorder_;
    std::size_t record_;
  };

  Scope host(StatName pass);
  Scope device(StatName pass);

  void count(StatName name, std::int64_t value) { stats_->set_count(name, value); }
  void add(StatName name, std::int64_t value) { stats_->add_count(name, value); }
  void figure(StatName name, double value) { stats_->set_figure(name, value); }

  // The frame's stats from now on (the scopes still open or uncollected go there too).
  void record_into(FrameStats& stats) { stats_ = &stats; }
  FrameStats& stats() const { return *stats_; }

  // Adds every finished scope's milliseconds to the stats (waiting for device timers where
  // there are some), and the device memory held; starts over.
  void collect();

 protected:
  // A device scope's start and end, and its milliseconds once collected. `timer`: what
  // begin_device returned. This class: none, the wall clock measures it.
  virtual int begin_device(StatName /*pass*/) { return -1; }
  virtual void end_device(int /*timer*/) {}
  virtual double device_ms(int /*timer*/) { return 0; }
  // After the times are collected: the device's memory into the stats, timers reused.
  virtual void end_collect(FrameStats& /*stats*/) {}

 private:
  struct Record {
    StatName pass;
    bool device = false;
    int timer = -1;   // begin_device's, when a device timer measures the scope
    double ms = 0;    // the wall clock's, when none does
    Stopwatch watch;  // from the scope's start
  };
  Scope open(StatName pass, bool device);
  void close(std::size_t record);

  FrameStats own_;
  FrameStats* stats_;
  std::vector<Record> records_;  // capacity kept from step to step
};

}  // namespace voxspan
