// insitu/live/live_server.h - the live page's HTTP server: a LiveFeed's snapshots, read-only, to
// whoever has the token.
//
// civetweb (Debian's libcivetweb-dev) runs it on threads of its own; nothing here runs on the
// solver's thread, which only publishes into the feed. What it serves is fixed at start and held
// in memory: `/` (the page, embedded in the binary), `/state.json` and `/view/<name>.png` for
// each view; no path reaches the file system (civetweb is given no document root). Its rules,
// all checked per request, in this order (docs/runtime.md, "The live page"):
//   - a bounded number of threads (kThreads) and of accepted connections waiting for one
//     (kQueuedConnections; beyond, the kernel's backlog), no keep-alive;
//   - the request head at most kMaxHeadBytes (civetweb answers 400), all of it read within
//     kRequestTimeoutMs (a client sending a byte a second is cut off), every write bounded by
//     the same time (a client reading a byte a second is cut off);
//   - at most kRequestsPerSecond requests a second per client address, in bursts of kBurst: 429;
//   - fewer than 64 headers (civetweb keeps 64 and drops the rest): 431;
//   - the token, compared in constant time, in `Authorization: Bearer <token>`, or for `/`
//     alone in `?token=<token>` (the URL printed at start): 401 otherwise;
//   - GET or HEAD only (405), no body (413; civetweb then reads and drops what the client
//     sends for up to two timeouts), a path of the fixed set (404).
#pragma once

#include <memory>
#include <string>

#include "insitu/config/config.h"
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

  // Listens on config.address:config.port (0: a free port); the token is config.token or, when
  // empty, 32 random bytes as hex. Throws voxspan::Error when it cannot listen.
  LiveServer(const LiveConfig& config, const LiveFeed& feed);
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
