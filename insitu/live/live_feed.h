// insitu/live/live_feed.h - what the live page shows, handed over by the solver's thread and made
// ready to serve on a thread of its own.
//
// In: each render step's pictures (SharedPicture references: no pixel is copied on the solver's
// thread), its step, time, particles and the milliseconds of each pass. Out: a LiveSnapshot,
// immutable, that any number of server threads read at once: the state as JSON and each view's
// latest picture as a PNG. The solver's thread only fills a mailbox under a mutex the feed's
// thread holds for a swap, never for work; a step that comes before the last is taken
// replaces it (the latest only), so a slow encoder never makes the solver wait; nor does the
// solver wake that thread: it looks for a new step every 50 ms, at a lower priority. Each step
// taken adds its row to the chart; the snapshot (the state and the pictures, encoded then) is
// made again at most every kSnapshotEveryMs (the page asks once a second) from the newest step,
// at once when the job ends. Once the pass names are known, publishing allocates nothing.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "insitu/views/view_products.h"

namespace voxspan {

// One render step as the pipeline hands it over.
struct LiveStep {
  std::int64_t step = 0;
  double time = 0;
  std::int64_t particles = 0;
  double in_situ_ms = 0;              // all of the step's in-situ work on the solver's thread
  std::span<const ViewResult> views;  // in the config's order; picture null where none
  std::span<const std::pair<const char*, double>> solver_passes;  // classify, compact, outputs
};

// What the server sends: made whole by the feed's thread, then only read.
struct LiveSnapshot {
  std::string state;                                         // JSON (see LiveFeed::state_json)
  std::vector<std::shared_ptr<const std::string>> pictures;  // PNG per view; null: none yet
};

class LiveFeed {
 public:
  // Steps kept for the chart: older ones are dropped first.
  static constexpr std::size_t kHistorySteps = 1000;
  // The least time between two snapshots: a job rendering 30 steps a second had the feed encode
  // every one, 5 % of a core for pictures the page fetches once a second.
  static constexpr int kSnapshotEveryMs = 250;
  // The niceness of the page's threads (the feed's and the server's): below the solver's, so
  // that encoding pictures and answering clients, hostile ones included, wait for a core the
  // solver leaves free.
  static constexpr int kThreadNice = 10;
  // Lowers the calling thread to kThreadNice.
  static void lower_priority();

  // `interactive`: the state says the page may turn the cameras (POST /camera).
  explicit LiveFeed(std::vector<std::string> view_names, bool interactive = false);
  ~LiveFeed();
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  // Solver's thread: takes references to the step's pictures and copies its numbers.
  void publish(const LiveStep& step);
  // The job has ended: the page says so.
  void finish();
  // Any thread: the latest snapshot; never null.
  std::shared_ptr<const LiveSnapshot> snapshot() const;
  const std::vector<std::string>& view_names() const { return names_; }

 private:
  // A step as handed over: what the mailbox holds and what the feed's thread works on.
  struct Handed {
    bool fresh = false;
    std::int64_t step = 0;
    double time = 0, in_situ_ms = 0;
    std::int64_t particles = 0;
    std::int64_t render_steps = 0;  // published so far, those the feed never took included
    std::chrono::steady_clock::time_point at;
    std::vector<SharedPicture> pictures;
    std::vector<std::pair<std::string, double>> passes;  // summed over the views
  };
  static void add_pass(Handed& h, std::string_view name, double ms);
  std::int64_t published_ = 0;  // under mailbox_mutex_
  void run();
  void take(Handed& work);
  void encode_waiting();
  std::string state_json() const;

  const std::vector<std::string> names_;
  const bool interactive_;
  mutable std::mutex mailbox_mutex_;
  std::condition_variable wake_;
  Handed mailbox_;
  bool finished_ = false, stopping_ = false;

  // The feed's thread only.
  struct History;
  std::unique_ptr<History> history_;

  mutable std::mutex snapshot_mutex_;
  std::shared_ptr<const LiveSnapshot> snapshot_;
  bool shown_finished_ = false;
  std::thread thread_;  // last: it starts with everything above made
};

}  // namespace voxspan
