// insitu/outputs/output.h - what an output is to the runtime: a kind of file written on its own
// trigger from what a render step produced. The runtime (insitu/runtime/pipeline.h) treats every
// output alike; each kind is one file in insitu/outputs/ and one line in
// insitu/runtime/registry.cpp (docs/design.md, "A new output").
//
// On a step where an output is due the runtime hands it the step (boundary particles, cell
// states, attributes) and each view's products (the picture, and what needs() asked for). The
// output copies what it keeps into pooled slots on the solver's thread (insitu/outputs/
// pooled_jobs.h) and hands the writing to the background writer, so the solver goes on at once
// and a run whose sizes are stable allocates nothing per step.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/config.h"
#include "insitu/outputs/formats/stats_record.h"
#include "insitu/outputs/writer/background_writer.h"
#include "insitu/parallel/communicator.h"
#include "insitu/views/view_products.h"
#include "voxspan/adapter.h"

namespace voxspan {

// Views seen from cameras turned about their target, rendered on a step where an output that
// asks for them is due, besides the views' own pictures (outputs.cinema). Angles in degrees:
// `phi` turns the view's own camera about its `up`, `theta` raises it (0, 0: the view's own).
struct OrbitRequest {
  std::vector<std::string> views;  // names; empty: every view
  std::vector<std::int64_t> phi, theta;
  bool depth = false;  // the first-hit distances too
};
struct OrbitPicture {
  std::size_t view = 0;
  std::int64_t phi = 0, theta = 0;
  SharedPicture picture;
  SharedPicture depth;  // null unless asked
};

struct OutputStep {
  const StepData& data;
  std::span<const ViewResult> views;
  const StatsRecord* record = nullptr;        // the step's stats, for outputs that report it
  std::span<const OrbitPicture> orbits = {};  // on a step where an output asking for them is due
};

// Files (or sets of files) handed over and written so far, for the summary.
struct OutputTally {
  std::int64_t submitted = 0;  // handed to the writer
  std::int64_t written = 0;    // complete on disk under their final names
  std::int64_t no_slot = 0;    // not handed over: every pooled slot was in flight
  double writer_seconds = 0;   // the writer thread's time in this output's jobs
};

// What an output is made with.
struct OutputContext {
  const Config& config;
  std::filesystem::path folder;  // its own, created and proved writable already
  std::span<const std::string> view_names;
  double particle_spacing = 0;  // the solver's rest spacing; 0 when unknown
  BackgroundWriter& writer;
  std::size_t slots = 0;  // pooled slots per kind of job (the writer's queue + 2)
  bool fsync = true;
  Communicator* comm = nullptr;  // the MPI job's ranks; null in one process
};

class Output {
 public:
  virtual ~Output() = default;
  // Copies what it needs and hands the write to the writer. Throws voxspan::Error on bad input
  // (the step reports it; the run goes on).
  virtual void write(const OutputStep& step) = 0;
  virtual OutputTally tally() const = 0;
  // At the end of the run, after the writer has drained.
  virtual void close() {}
};

struct OutputKind {
  OutputConfigKind config;
  std::string_view noun;  // what the summary counts: "PNG", "VTK sets"
  // What the views must produce when it is due; a picture or a depth image makes the step a
  // render step even when the render trigger is not due, and with no views it never is due.
  ViewNeeds needs;
  // An output of the step's own stats: handed the step last, with the record filled.
  bool reports_step = false;
  // Made on the root rank only in an MPI job (the pictures and the stats exist there); the
  // others write their own part (snapshots gather to the root themselves).
  bool root_only = false;
  std::function<std::unique_ptr<Output>(const OutputSettings&, const OutputContext&)> make;
  // The orbits its settings ask for (null: none), rendered on every rank.
  std::function<OrbitRequest(const OutputSettings&)> orbits = {};
};

// The kind of output O, whose settings type S is read by `section`.
template <class S, class O>
OutputKind output_kind(std::string_view name, std::string_view noun,
                       const schema::Section<S>& section, ViewNeeds needs = {},
                       bool reports_step = false, bool root_only = false) {
  return {config_kind<OutputSettings>(name, section),
          noun,
          needs,
          reports_step,
          root_only,
          [](const OutputSettings& s, const OutputContext& c) -> std::unique_ptr<Output> {
            return std::make_unique<O>(dynamic_cast<const S&>(s), c);
          }};
}

// "<prefix>_<step, 8 digits>.<extension>": sorts by step, and ffmpeg's glob input takes it.
std::string step_file_name(std::string_view prefix, std::int64_t step, std::string_view extension);

}  // namespace voxspan
