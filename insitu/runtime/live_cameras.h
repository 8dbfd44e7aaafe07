// insitu/runtime/live_cameras.h - the views' cameras as the live page turns them
// (`live.interactive`): the solver itself is never steered, only what the views look from.
//
// At the start of each render step, on the solver's thread, the changes the page asked for
// since the last one are taken from the server's mailbox (insitu/live/camera_mailbox.h: one
// atomic load when there is none) and, in an MPI job, broadcast from the root, which alone runs
// the server, so that every rank renders with the same camera (one broadcast of a few bytes a
// view per render step). Each view keeps the user's offset (insitu/views/camera_offset.h) on
// top of its framing until a reset. An applied change is logged with the camera it gives: on
// the root at the warning level (shown by default: the job's log says what the page did), on
// the other ranks at the debug level (a test compares them). Nothing allocated after start.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "insitu/live/camera_mailbox.h"
#include "insitu/parallel/communicator.h"
#include "insitu/views/camera_offset.h"

namespace voxspan {

class LiveCameras {
 public:
  // `mailbox`: the server's, on the root (null on the other ranks); `comm`: null in one
  // process.
  LiveCameras(std::vector<std::string> view_names, CameraMailbox* mailbox, Communicator* comm);

  // Every rank, at the start of a render step: what was asked since the last one.
  void take();
  // View `view`'s camera on this step: its framing's, with the user's offset (turned about
  // `pivot`, ViewFraming::pivot()).
  Camera camera(std::size_t view, const Camera& framed, glm::dvec3 pivot);

 private:
  const std::vector<std::string> names_;
  CameraMailbox* const mailbox_;
  Communicator* const comm_;
  std::vector<CameraChange> changes_;  // taken, not yet applied; zero once applied
  std::vector<CameraOffset> offsets_;
};

}  // namespace voxspan
