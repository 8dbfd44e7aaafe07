// insitu/live/live_server.h - the live page's HTTP server: a LiveFeed's snapshots to whoever has
// the token, and with `live.interactive` the views' cameras turned from the page.
//
// civetweb (Debian's libcivetweb-dev) runs it on threads of its own; nothing here runs on the
// solver's thread, which only publishes into the feed (and, when interactive, takes from the
// camera mailbox). What it serves is fixed at start and held in memory: `/` (the page, embedded
// in the binary), `/state.json` and `/view/<name>.png` for each view, and `/camera` (POST) when
// interactive; no path reaches the file system (civetweb is given no document root). Its
// rules, all checked per request, in this order (docs/runtime.md, "The live page"):
//   - a bounded number of threads (kThreads) and of accepted connections waiting for one
//     (kQueuedConnections; beyond, the kernel's backlog), no keep-alive;
//   - the request head at most kMaxHeadBytes (civetweb answers 400), all of it read within
//     kRequestTimeoutMs (a client sending a byte a second is cut off), every write bounded by
//     the same time (a client reading a byte a second is cut off);
//   - at most kRequestsPerSecond requests a second per client address, in bursts of kBurst: 429;
//   - fewer than 64 headers (civetweb keeps 64 and drops the rest): 431;
//   - the token, compared in constant time, in `Authorization: Bearer <token>`, or for `/`
//     alone in `?token=<token>` (the URL printed at start): 401 otherwise;
//   - `/camera`: 403 unless interactive; POST only (405), a form body (415) of a stated length
//     (411) of at most kMaxCameraBodyBytes (413) that parse_camera_request accepts (400); it is
//     merged into the mailbox (202), nothing more;
//   - any other path: GET or HEAD only (405), no body (413; civetweb then reads and drops what
//     the client sends for up to two timeouts), a path of the fixed set (404).
#pragma once

#include <memory>
#include <string>

#include "insitu/config/config.h"
#include "insitu/live/camera_mailbox.h"
#include "insitu/live/live_feed.h"

namespace voxspan {

class LiveServer {
 public:
  static constexpr int kThreads = 8;
  static constexpr int kQueuedConnections = 32;
  static constexpr int kMaxHeadBytes = 8192;
  static constexpr int kRequestTimeoutMs = 5000;
  static constexpr double kRequestsPerSecond = 50;
  static constexpr double kBurst = 100;
  static constexpr int kMaxCameraBodyBytes = 1024;

  // Listens on config.address:config.port (0: a free port); the token is config.token or, when
  // empty, 32 random bytes as hex. `cameras`: where POST /camera goes (null: read-only; it
  // must outlive the server). Throws voxspan::Error when it cannot listen.
  LiveServer(const LiveConfig& config, const LiveFeed& feed, CameraMailbox* cameras = nullptr);
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const;
  const std::string& token() const;
  // http://<address>:<port>/?token=<token>: what the user opens.
  std::string url() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxspan
