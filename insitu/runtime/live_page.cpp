#include "insitu/runtime/live_page.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "insitu/runtime/step_record.h"
#include "voxspan/log.h"
#include "voxspan/stopwatch.h"

namespace voxspan {

LivePage::LivePage(const LiveConfig& config, std::vector<std::string> view_names, bool serves,
                   Communicator* comm)
    : linger_seconds_(config.linger_seconds) {
  if (serves) {
    feed_ = std::make_unique<LiveFeed>(view_names, config.interactive);
    if (config.interactive) mailbox_ = std::make_unique<CameraMailbox>(view_names.size());
    server_ = std::make_unique<LiveServer>(config, *feed_, mailbox_.get());
    // Said once, at a level shown by default: the token is in it (as Jupyter prints its URL).
    // A log level that hides warnings would leave the page unreachable: it is said anyway.
    log_message(std::min(LogLevel::warning, log_level()), "live page: " + server_->url());
  }
  if (config.interactive) cameras_.emplace(std::move(view_names), mailbox_.get(), comm);
}

double LivePage::publish(const StepData& data, const StepStats& stats,
                         std::span<const ViewResult> views, double outputs_ms, double process_ms) {
  if (!feed_) return 0;
  const Stopwatch handing;
  passes_[0].second = 1e3 * stats.seconds_classify;
  passes_[1].second = 1e3 * stats.seconds_compact;
  passes_[2].second = outputs_ms;
  feed_->publish({data.step, data.time, std::int64_t(stats.counts.particles),
                  in_situ_ms(stats, process_ms), views, passes_});
  return handing.seconds();
}

void LivePage::finish() {
  if (!feed_ || finished_) return;
  finished_ = true;
  feed_->finish();
  if (linger_seconds_ <= 0) return;
  log_warning("live page: kept up ", linger_seconds_, " s after the last step");
  std::this_thread::sleep_for(std::chrono::duration<double>(linger_seconds_));
}

}  // namespace voxspan
