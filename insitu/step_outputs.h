// insitu/step_outputs.h - the files of a render step, written on the background writer's
// thread: a PNG per view, the stats line, an OpenVDB snapshot, the VTK files and their .pvd
// series (docs/runtime.md, "Files and their guarantees").
//
// What a job needs is copied, on the solver's thread, into a pooled slot (insitu/slot_pool.h)
// whose vectors keep their capacity, so that a run whose sizes are stable allocates nothing
// per step for it; the job releases the slot when it ends. A full queue follows the writer's
// policy: `wait` blocks the solver, `drop` skips the file and counts it. A failed write is the
// writer's to report (once per kind of error); the run goes on.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "insitu/background_writer.h"
#include "insitu/config.h"
#include "insitu/particle_data.h"
#include "insitu/slot_pool.h"
#include "insitu/stats.h"
#include "insitu/stats_log.h"
#include "insitu/view_renderer.h"
#include "insitu/vtk_files.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"

namespace voxspan {

// Files written so far (complete, under their final names), per kind.
struct OutputCounts {
  std::int64_t png = 0, stats = 0, vdb = 0, vtk = 0;
  double writer_seconds = 0;  // time the writer thread spent in the jobs
};

class StepOutputs {
 public:
  // Opens the stats file (the folders must have been checked: prepare_output_folders) and
  // starts the writer thread. `spacing` (0 when unknown) sizes the snapshot's spheres.
  StepOutputs(const Config& config, std::vector<std::string> view_names, double spacing);
  ~StepOutputs();
  StepOutputs(const StepOutputs&) = delete;
  StepOutputs& operator=(const StepOutputs&) = delete;

  // A view's picture is rendered into acquire_frame()'s image, then handed over with
  // submit_png (or given back with release_frame when rendering failed). nullptr when no slot
  // is free: the frame is dropped and counted.
  struct Frame {
    ViewImage image;
    std::size_t view = 0;
    std::int64_t step = 0;
  };
  Frame* acquire_frame();
  void release_frame(Frame* frame);
  bool submit_png(std::size_t view, std::int64_t step, Frame* frame);

  bool submit_stats(const StatsRecord& record);
  bool submit_vdb(const StepData& data);
  bool submit_vtk(const StepData& data);

  // Waits until every file handed over is written (or has failed).
  void drain();
  WriterStats writer_stats() const { return writer_.stats(); }
  OutputCounts counts() const;
  // Frames that found no free slot (the writer's own drops are in writer_stats()).
  std::int64_t frames_without_slot() const { return frames_without_slot_; }

 private:
  using FrameSlot = Frame;
  struct SnapshotSlot;
  struct StatsSlot;
  void copy_snapshot(const StepData& data, const std::vector<std::string>& attributes,
                     double radius, SnapshotSlot& slot) const;
  // A slot of `pool` holding the step's copy; nullptr when none is free.
  SnapshotSlot* filled_snapshot(SlotPool<SnapshotSlot>& pool, const StepData& data,
                                const std::vector<std::string>& names, double radius) const;
  // Hands `slot` to the writer; the job runs Write on it and gives it back to Pool.
  template <class Slot, std::unique_ptr<SlotPool<Slot>> StepOutputs::*Pool,
            void (StepOutputs::*Write)(Slot&)>
  bool submit(Slot* slot, const char* label);
  void write_png_job(FrameSlot& slot);
  void write_stats_job(StatsSlot& slot);
  void write_vdb_job(SnapshotSlot& slot);
  void write_vtk_job(SnapshotSlot& slot);

  const Config config_;
  const std::vector<std::string> view_names_;
  const double vdb_radius_;  // 0: the spheres' own radii
  std::filesystem::path png_folder_, vdb_folder_, vtk_folder_;
  std::unique_ptr<StatsLog> stats_log_;
  std::unique_ptr<PvdSeries> particles_pvd_, cells_pvd_;
  std::unique_ptr<SlotPool<FrameSlot>> frames_;
  std::unique_ptr<SlotPool<SnapshotSlot>> vdb_slots_, vtk_slots_;
  std::unique_ptr<SlotPool<StatsSlot>> stats_slots_;
  std::atomic<std::int64_t> png_written_{0}, stats_written_{0}, vdb_written_{0}, vtk_written_{0};
  std::atomic<std::int64_t> writer_microseconds_{0};
  std::int64_t frames_without_slot_ = 0;
  BackgroundWriter writer_;  // last: its thread stops (draining) before the rest goes
};

}  // namespace voxspan
