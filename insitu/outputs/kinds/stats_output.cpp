// outputs.stats: the step's stats record (insitu/outputs/formats/stats_record.h) as one JSON line
// of <folder>/<file>. The line is made on the solver's thread into a pooled string and appended on
// the writer's (insitu/outputs/formats/stats_log.h: a failed write never leaves half a line).
#include "insitu/outputs/formats/stats_log.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/pooled_jobs.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

struct StatsSettings : CloneAs<StatsSettings, OutputSettings> {
  StatsSettings() : CloneAs(true, ".", TriggerSpec{10, 0, true, true}) {
    follows_render_trigger = true;
  }
  std::string file = "stats.jsonl";
  bool operator==(const StatsSettings&) const = default;
};

void check_stats(yaml::MapReader& r, StatsSettings& s) {
  if (r.has("file") && !schema::is_plain_name(s.file))
    r.checker().error(r.find("file"), r.path("file"),
                      "must be a plain file name (the folder is outputs.stats.folder)");
}

const schema::Section<StatsSettings>& stats_section() {
  static const schema::Section<StatsSettings> s{
      "outputs.stats",
      output_keys<StatsSettings>({schema::text("file", &StatsSettings::file, "plain file name")},
                                 "the render trigger"),
      check_stats};
  return s;
}

class StatsOutput final : public Output {
 public:
  StatsOutput(const StatsSettings& s, const OutputContext& c)
      : log_(c.folder / s.file), jobs_(c.writer, c.slots, [this](Line& l) { append(l); }) {}
  ~StatsOutput() override { close(); }

  void write(const OutputStep& step) override {
    if (step.record == nullptr) throw make_error("stats output: the step has no record");
    jobs_.submit("stats line", [&](Line& l) {
      l.text.clear();
      append_json_line(*step.record, l.text);
      // The numbers change length from step to step (a pass of 9.87 ms, then 10.02): room to
      // spare, so that a slightly longer line later needs no new memory. (Without it, a slot
      // grew now and then once sizes were stable: the one-off allocation StepAllocations saw.)
      if (l.text.capacity() < l.text.size() + l.text.size() / 4)
        l.text.reserve(l.text.size() + l.text.size() / 2);
    });
  }

  OutputTally tally() const override { return jobs_.tally(); }

  void close() override {
    try {
      log_.sync();
      // No line ever written (a run that failed before its first report): no empty file left.
      if (jobs_.tally().submitted == 0) log_.remove_if_empty();
    } catch (const std::exception& e) {
      log_warning("stats file: ", e.what());
    }
  }

 private:
  struct Line {
    std::string text;
  };
  void append(const Line& l) { log_.append(l.text); }

  StatsLog log_;
  PooledJobs<Line> jobs_;
};

}  // namespace

OutputKind stats_output_kind() {
  return output_kind<StatsSettings, StatsOutput>("stats", "stats lines", stats_section(), {},
                                                 /*reports_step=*/true, /*root_only=*/true);
}

}  // namespace voxspan
