#include "insitu/live/live_feed.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <deque>

#include "insitu/outputs/formats/json_text.h"
#include "insitu/outputs/formats/png_image.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

constexpr int kPollMs = 50;  // how often the feed's thread looks for a step handed over

}  // namespace

struct LiveFeed::History {
  struct Row {
    std::int64_t step = 0;
    std::vector<double> ms;  // by pass, in `passes`' order
  };
  std::vector<std::string> passes;  // in order of first report
  std::deque<Row> rows;
  std::int64_t step = -1, particles = 0, render_steps = 0;
  double time = 0, in_situ_ms = 0, sum_in_situ_ms = 0;
  std::chrono::steady_clock::time_point start;  // when the first step's in-situ work began
  double wall_ms = 0;  // from `start` to the latest step's end: in situ and the solver
  struct Shown {
    std::int64_t step = -1;
    int width = 0, height = 0;
  };
  std::vector<Shown> views;
  std::vector<std::shared_ptr<const std::string>> pictures;
  // The newest picture of each view not yet encoded, and its step.
  struct Waiting {
    SharedPicture picture;
    std::int64_t step = -1;
  };
  std::vector<Waiting> waiting;

  std::size_t pass_index(const std::string& name) {
    for (std::size_t i = 0; i < passes.size(); ++i)
      if (passes[i] == name) return i;
    passes.push_back(name);
    return passes.size() - 1;
  }
};

LiveFeed::LiveFeed(std::vector<std::string> view_names, bool interactive)
    : names_(std::move(view_names)),
      interactive_(interactive),
      history_(std::make_unique<History>()) {
  mailbox_.pictures.resize(names_.size());
  history_->views.resize(names_.size());
  history_->pictures.resize(names_.size());
  history_->waiting.resize(names_.size());
  snapshot_ = std::make_shared<const LiveSnapshot>(LiveSnapshot{state_json(), history_->pictures});
  thread_ = std::thread([this] { run(); });
}

LiveFeed::~LiveFeed() {
  {
    std::lock_guard lock(mailbox_mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void LiveFeed::add_pass(Handed& h, std::string_view name, double ms) {
  for (auto& [n, v] : h.passes)
    if (n == name) {
      v += ms;
      return;
    }
  h.passes.emplace_back(std::string(name), ms);  // a pass first seen: once per name
}

void LiveFeed::publish(const LiveStep& step) {
  {
    std::lock_guard lock(mailbox_mutex_);
    Handed& h = mailbox_;
    h.fresh = true;
    h.step = step.step;
    h.time = step.time;
    h.particles = step.particles;
    h.in_situ_ms = step.in_situ_ms;
    h.render_steps = ++published_;
    h.at = std::chrono::steady_clock::now();
    for (auto& pass : h.passes) pass.second = 0;
    for (const auto& [name, ms] : step.solver_passes) add_pass(h, name, ms);
    for (std::size_t i = 0; i < step.views.size() && i < h.pictures.size(); ++i) {
      const ViewResult& v = step.views[i];
      // Reassigned in place: the reference the mailbox held before goes back to its pool.
      if (v.shared_picture != nullptr) h.pictures[i] = *v.shared_picture;
      else h.pictures[i].reset();
      if (v.stats != nullptr)
        for (const FrameStats::Pass& p : v.stats->passes) add_pass(h, p.name, p.ms);
    }
  }
  // No notify: a woken thread may take the solver's core at once (measured: 0.5 ms a step on
  // average, 5 ms at most, on two busy cores). The feed's thread looks every kPollMs instead.
}

void LiveFeed::finish() {
  {
    std::lock_guard lock(mailbox_mutex_);
    finished_ = true;
  }
  wake_.notify_one();
}

std::shared_ptr<const LiveSnapshot> LiveFeed::snapshot() const {
  std::lock_guard lock(snapshot_mutex_);
  return snapshot_;
}

void LiveFeed::lower_priority() {
  setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kThreadNice);
}

void LiveFeed::run() {
  lower_priority();
  Handed work;
  work.pictures.resize(names_.size());
  bool finished = false;
  bool due = false;  // a step taken, or the end, that the snapshot does not show yet
  std::chrono::steady_clock::time_point made;  // the last snapshot's; none: long ago
  for (;;) {
    {
      std::unique_lock lock(mailbox_mutex_);
      wake_.wait_for(lock, std::chrono::milliseconds(kPollMs),
                     [&] { return mailbox_.fresh || stopping_ || finished_ != finished; });
      if (stopping_) return;
      if (mailbox_.fresh || finished_ != finished) {
        finished = finished_;
        // A view's picture still waiting goes before its newer one comes: the page never holds
        // more than two of a view's buffers (the pipeline reserves for that).
        for (std::size_t i = 0; i < mailbox_.pictures.size(); ++i)
          if (mailbox_.pictures[i]) history_->waiting[i].picture.reset();
        // A swap: both keep their storage, and the mailbox gets back pictures already dropped.
        std::swap(work, mailbox_);
        mailbox_.fresh = false;
        due = true;
      }
    }
    if (work.fresh) take(work);
    const auto now = std::chrono::steady_clock::now();
    // Once the job has ended, its last step at once.
    if (!due || (!finished && now - made < std::chrono::milliseconds(kSnapshotEveryMs))) continue;
    due = false;
    made = now;
    encode_waiting();
    auto next = std::make_shared<LiveSnapshot>();
    next->pictures = history_->pictures;
    {
      std::lock_guard lock(snapshot_mutex_);
      shown_finished_ = finished;
    }
    next->state = state_json();
    std::lock_guard lock(snapshot_mutex_);
    snapshot_ = std::move(next);
  }
}

// Adds the step's row to the chart and keeps its pictures, the newest of each view, to encode.
void LiveFeed::take(Handed& work) {
  History& h = *history_;
  if (h.step < 0)
    h.start = work.at - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double, std::milli>(work.in_situ_ms));
  h.step = work.step;
  h.time = work.time;
  h.particles = work.particles;
  h.in_situ_ms = work.in_situ_ms;
  h.sum_in_situ_ms += work.in_situ_ms;
  h.wall_ms = std::chrono::duration<double, std::milli>(work.at - h.start).count();
  h.render_steps = work.render_steps;  // a step handed over before the last was taken counts
  History::Row row{work.step, std::vector<double>(h.passes.size(), 0.0)};
  for (const auto& [name, ms] : work.passes) {
    const std::size_t i = h.pass_index(name);
    if (i >= row.ms.size()) row.ms.resize(i + 1, 0.0);
    row.ms[i] = ms;
  }
  h.rows.push_back(std::move(row));
  if (h.rows.size() > kHistorySteps) h.rows.pop_front();
  for (std::size_t i = 0; i < work.pictures.size(); ++i) {
    if (!work.pictures[i]) continue;  // none this step: the view's older one, if any, stays
    h.waiting[i] = {std::move(work.pictures[i]), work.step};
  }
  work.fresh = false;
}

// Encodes the pictures waiting and drops their references.
void LiveFeed::encode_waiting() {
  History& h = *history_;
  for (std::size_t i = 0; i < h.waiting.size(); ++i) {
    SharedPicture& p = h.waiting[i].picture;
    if (!p) continue;
    try {
      const ImageRGBA8& picture = *p.srgb8();
      h.pictures[i] = std::make_shared<const std::string>(encode_png(picture));
      h.views[i] = {h.waiting[i].step, picture.width, picture.height};
    } catch (const std::exception& e) {
      log_warning("live page: view ", names_[i], ": ", e.what());
    }
    p.reset();
  }
}

// {"running":true,"interactive":false,"step":120,"time":0.6,"particles":100000,"render_steps":13,
//  "in_situ_ms":41.2,"in_situ_share":0.18,"views":[{"name":"main","step":120,"width":960,
//  "height":540}],"passes":["classify",...],"history":[[120,3.1,...],...]}
std::string LiveFeed::state_json() const {
  const History& h = *history_;
  std::string s = "{\"running\":";
  s += shown_finished_ ? "false" : "true";
  s += interactive_ ? ",\"interactive\":true" : ",\"interactive\":false";
  s += ",\"step\":" + std::to_string(h.step);
  s += ",\"time\":";
  append_number(s, h.time);
  s += ",\"particles\":" + std::to_string(h.particles);
  s += ",\"render_steps\":" + std::to_string(h.render_steps);
  s += ",\"in_situ_ms\":";
  append_number(s, h.in_situ_ms);
  s += ",\"in_situ_share\":";
  // As the dam break's summary says it: in-situ time over the solver's own (the rest).
  const double solver_ms = h.wall_ms - h.sum_in_situ_ms;
  append_number(s, solver_ms > 0 ? h.sum_in_situ_ms / solver_ms : 0.0);
  s += ",\"views\":[";
  for (std::size_t i = 0; i < names_.size(); ++i) {
    s += i ? ",{\"name\":" : "{\"name\":";
    append_string(s, names_[i]);
    s += ",\"step\":" + std::to_string(h.views[i].step) +
         ",\"width\":" + std::to_string(h.views[i].width) +
         ",\"height\":" + std::to_string(h.views[i].height) + "}";
  }
  s += "],\"passes\":[";
  for (std::size_t i = 0; i < h.passes.size(); ++i) {
    if (i) s += ',';
    append_string(s, h.passes[i]);
  }
  s += "],\"history\":[";
  bool first = true;
  for (const History::Row& row : h.rows) {
    s += first ? "[" : ",[";
    first = false;
    s += std::to_string(row.step);
    for (std::size_t i = 0; i < h.passes.size(); ++i) {
      s += ',';
      append_number(s, i < row.ms.size() ? row.ms[i] : 0.0);
    }
    s += ']';
  }
  s += "]}";
  return s;
}

}  // namespace voxspan
