#include "insitu/runtime/live_cameras.h"

#include <type_traits>

#include "voxspan/log.h"

namespace voxspan {

// Broadcast as bytes: every rank runs the same build.
static_assert(std::is_trivially_copyable_v<CameraChange>);

LiveCameras::LiveCameras(std::vector<std::string> view_names, CameraMailbox* mailbox,
                         Communicator* comm)
    : names_(std::move(view_names)),
      mailbox_(mailbox),
      comm_(comm),
      changes_(names_.size()),
      offsets_(names_.size()) {}

void LiveCameras::take() {
  if (mailbox_ != nullptr) mailbox_->take(changes_);
  if (comm_ != nullptr && comm_->size() > 1)
    comm_->broadcast(std::as_writable_bytes(std::span(changes_)));
}

Camera LiveCameras::camera(std::size_t view, const Camera& framed, glm::dvec3 pivot) {
  CameraChange& change = changes_[view];
  if (!change.any()) return offsets_[view].on(framed, pivot);
  offsets_[view].add(change, framed);
  const Camera c = offsets_[view].on(framed, pivot);
  const LogLevel level = comm_ == nullptr || comm_->root() ? LogLevel::warning : LogLevel::debug;
  log(level, "view ", names_[view], ": camera turned from the live page (", change.requests,
      change.requests == 1 ? " request" : " requests", change.reset != 0 ? ", reset" : "",
      "): eye (", c.eye.x, ", ", c.eye.y, ", ", c.eye.z, "), target (", c.target.x, ", ",
      c.target.y, ", ", c.target.z, ")");
  change = {};
  return c;
}

}  // namespace voxspan
