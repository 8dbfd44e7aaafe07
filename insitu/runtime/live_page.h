// insitu/runtime/live_page.h - the live page (`live`, insitu/live/) as the pipeline runs it:
// its feed and HTTP server on the root rank, the cameras the page turns (`live.interactive`) on
// every rank, the solver-thread passes it shows, and the linger after the last step.
//
// Made once at start; after the first step nothing here allocates. The pipeline destroys it
// before the views' picture pools: the feed holds references to their pictures.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "insitu/config/config.h"
#include "insitu/live/camera_mailbox.h"
#include "insitu/live/live_feed.h"
#include "insitu/live/live_server.h"
#include "insitu/runtime/live_cameras.h"
#include "voxspan/adapter.h"

namespace voxspan {

class Communicator;

class LivePage {
 public:
  // `serves`: this rank runs the server (the root, or the only process); `comm` null in one
  // process. Starts the server and says its address (with the token) at the warning level.
  LivePage(const LiveConfig& config, std::vector<std::string> view_names, bool serves,
           Communicator* comm);
  LivePage(const LivePage&) = delete;
  LivePage& operator=(const LivePage&) = delete;

  // This rank hands the page its pictures (every render step's, as 8-bit sRGB).
  bool feeds() const { return feed_ != nullptr; }

  // Every rank, at the start of a render step: the camera changes asked since the last one.
  void take_cameras() {
    if (cameras_) cameras_->take();
  }
  // View `view`'s camera on this step: `framed`, turned by the page's offset when interactive.
  Camera camera(std::size_t view, const Camera& framed, glm::dvec3 pivot) {
    return cameras_ ? cameras_->camera(view, framed, pivot) : framed;
  }

  // The solver's thread hands over references and a few numbers (insitu/live/live_feed.h);
  // the seconds it took come back.
  double publish(const StepData& data, const StepStats& stats, std::span<const ViewResult> views,
                 double outputs_ms, double process_ms);

  // After the last step: the final page, kept up `linger_seconds` when asked. Once.
  void finish();

 private:
  const double linger_seconds_;
  // In this order: the server goes first, so that no request reads the feed after it.
  std::unique_ptr<LiveFeed> feed_;          // where this rank serves
  std::unique_ptr<CameraMailbox> mailbox_;  // where it serves an interactive page
  std::unique_ptr<LiveServer> server_;
  std::optional<LiveCameras> cameras_;  // on every rank, when it is interactive
  std::array<std::pair<const char*, double>, 3> passes_{
      {{"classify", 0}, {"compact", 0}, {"outputs", 0}}};
  bool finished_ = false;
};

}  // namespace voxspan
