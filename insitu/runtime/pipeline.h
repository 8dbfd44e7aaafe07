// insitu/runtime/pipeline.h - the runtime behind the adapter (voxspan/adapter.h, Pipeline): on
// each step the config's triggers choose the work (insitu/runtime/schedule.h); on a render step
// every view is framed (insitu/views/view_framing.h) and rendered by its kind
// (insitu/views/view.h), then every output that is due gets the step and the views' products
// (insitu/outputs/output.h) and hands its files to the background writer; the stats output
// comes last, with the step's record.
//
// Everything that can fail before step 1 fails in the constructor, with a voxspan::Error that
// names the problem: the output folders are created and proved writable, the GL context is
// made (renderer.gl_platform; VOXSPAN_GL_PLATFORM overrides it) and every pass is compiled.
// After that nothing throws into the solver: a failed view or file is a Status or a counted
// writer error, and the run goes on. Once sizes are stable a render step allocates no new
// buffers: GPU buffers, read-back images, job slots and the stats record are reused.
// GL: the context is current on the thread that made the pipeline; a step on another thread
// makes it current there.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "insitu/config/config.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/background_writer.h"
#include "insitu/parallel/communicator.h"
#include "render/frame_stats.h"
#include "voxspan/adapter.h"

namespace voxspan {

// What one output did so far.
struct OutputTotals {
  std::string kind;
  std::string_view noun;  // "PNG", "VTK sets"
  bool enabled = false;
  OutputTally tally;
  std::int64_t due = 0;  // steps its trigger fired (0 at the end: a trigger that never did)
};

// What the run did so far.
struct PipelineTotals {
  std::int64_t render_steps = 0;      // steps where the views were rendered
  std::int64_t frames = 0;            // views rendered (all render steps)
  std::int64_t failed_views = 0;      // view renders that threw
  double seconds_render = 0;          // solver's thread: framing, rendering, read-back
  double seconds_outputs = 0;         // solver's thread: copies into job slots, submits (and waits)
  double seconds_process = 0;         // solver's thread: all of process()
  double seconds_live = 0;            // solver's thread: handing render steps to the live page
  FrameStats passes;                  // milliseconds per pass, summed over all views and steps
  std::vector<OutputTotals> outputs;  // every output kind, in the config's order
  WriterStats writer;

  // The output of that kind (every kind has one).
  const OutputTally& output(std::string_view kind) const;
  double writer_seconds() const;  // the writer thread's time in every output's jobs
};

class InsituPipeline final : public Pipeline {
 public:
  // `particle_spacing`: the solver's rest spacing (0 when unknown: then every view needs its
  // gap and filter_radius set). `mpi_comm`: the job's communicator (Fortran handle; voxspan/
  // mpi.h), when the runtime runs on every rank of it. Throws voxspan::Error (see above), on
  // every rank alike.
  InsituPipeline(const Config& config, double particle_spacing,
                 std::optional<int> mpi_comm = std::nullopt);
  ~InsituPipeline() override;

  bool wants_step(std::int64_t step, double time) override;
  bool confirm_step(std::int64_t step, double time, const ParticleView& particles) override;
  Status agree(const Status& local) override;
  std::array<double, 3> agree_point(const std::array<double, 3>& local) override;
  bool reports_failures() const override;
  void mark_last_step(std::int64_t step) override;
  Status process(const StepData& data, const StepStats& stats) override;
  void finish() override;
  std::string summary() const override;

  PipelineTotals totals() const;
  const Config& config() const;
  // The latest render step's views (name and picture; the picture is null where the view
  // failed, its read-back failed (said in the log) or, in an MPI job, on every rank but the
  // root), valid until the next step. Waits for pictures still on their way from the GPU.
  // A picture only 8-bit readers took (PNG files, the live page) came as 8-bit sRGB from a GL
  // renderer; its floats are those bytes decoded unless the caller keeps linear pictures.
  std::span<const ViewResult> latest_views() const;
  // From the next render step on, every picture comes as the shading's linear floats, for a
  // caller that reads them (latest_views(); Python's pictures(linear=True)).
  void keep_linear_pictures(bool keep = true);
  // One line: the GL platform and renderer, the views and the enabled outputs.
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Communicator> comm_;  // before impl_, which uses it; null in one process
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxspan
