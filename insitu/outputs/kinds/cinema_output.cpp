// outputs.cinema: a Cinema image database (specification D, the format ParaView Catalyst and
// Ascent write and the Cinema viewers read) for exploring a run afterwards. On each step it is
// due, each view it names is seen from every (phi, theta) of its camera turned about its target
// (OrbitRequest, insitu/outputs/output.h; 0, 0 is the view's own camera):
//   <folder>/<step, 8 digits>/<view>_p<phi>_t<theta>.png  (and .exr, the distances, with `depth`)
// and <folder>/data.csv lists every picture written so far, one row each:
//   time,step,view,phi,theta,FILE[,FILE_depth]
// with FILE relative to the folder. The pictures are rendered on every rank (the views'
// composites are collective) and written from the root; the step's pictures go to the writer
// as one job holding references to them (no copy), which writes them, then data.csv again,
// atomically: a row appears only once its files are whole on disk.
#include <filesystem>
#include <sstream>

#include "insitu/outputs/formats/exr_image.h"
#include "insitu/outputs/formats/png_image.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {
namespace {

struct CinemaSettings : CloneAs<CinemaSettings, OutputSettings> {
  CinemaSettings() : CloneAs(false, "cinema.cdb", TriggerSpec{100, 0, false, true}) {}
  std::vector<std::string> views;  // empty: every view
  std::vector<std::int64_t> phi{-90, -45, 0, 45, 90};
  std::vector<std::int64_t> theta{0, 30};
  bool depth = false;
  std::span<const std::string> named_views() const override { return views; }
  bool operator==(const CinemaSettings&) const = default;
};

const schema::Section<CinemaSettings>& cinema_section() {
  using S = CinemaSettings;
  static const schema::Section<S> s{
      "outputs.cinema",
      output_keys<S>(
          {schema::names("views", &S::views, "the views seen from every angle; empty: all"),
           schema::integers("phi", &S::phi, -180, 180,
                            "degrees the view's camera turns about its `up`, around its target"),
           schema::integers("theta", &S::theta, -89, 89,
                            "degrees the camera is raised towards its `up` (its elevation stops "
                            "1 degree short of straight above or below)"),
           schema::flag("depth", &S::depth,
                        "each picture's first-hit distances too, as OpenEXR (channel Z), in "
                        "column FILE_depth")}),
      [](yaml::MapReader& r, S& v) {
        for (const char* key : {"phi", "theta"})
          if (r.has(key) && (key[0] == 'p' ? v.phi : v.theta).empty())
            r.checker().error(r.find(key), r.path(key), "needs at least one angle");
        if (!std::filesystem::path(v.folder).extension().string().ends_with(".cdb"))
          r.checker().error(r.has("folder") ? r.find("folder") : r.node(), r.path("folder"),
                            "a Cinema database's folder ends in .cdb (spec D: the viewers open "
                            "only such folders); got \"" +
                                v.folder + "\"");
        // One picture per angle: -180 and 180 are one turn (a value given twice is refused
        // as any list's).
        const auto same_turn = [](std::int64_t a, std::int64_t b) { return (a - b) % 360 == 0; };
        for (std::size_t i = 0; i < v.phi.size(); ++i)
          for (std::size_t j = i + 1; j < v.phi.size(); ++j)
            if (same_turn(v.phi[i], v.phi[j])) {
              r.checker().error(r.find("phi"), r.path("phi"),
                                std::to_string(v.phi[i]) + " and " + std::to_string(v.phi[j]) +
                                    " are the same angle: the database would hold the picture "
                                    "twice");
              return;
            }
      }};
  return s;
}

class CinemaOutput final : public Output {
 public:
  CinemaOutput(const CinemaSettings& s, const OutputContext& c)
      : folder_(c.folder),
        view_names_(c.view_names.begin(), c.view_names.end()),
        depth_(s.depth),
        sync_(c.fsync),
        jobs_(c.writer, c.slots, [this](Slot& slot) { run(slot); }) {
    rows_.precision(17);  // the time as the solver had it
    rows_ << "time,step,view,phi,theta,FILE" << (depth_ ? ",FILE_depth" : "") << "\n";
  }

  void write(const OutputStep& step) override {
    if (step.orbits.empty()) return;
    jobs_.submit("Cinema step", [&](Slot& slot) {
      slot.step = step.data.step;
      slot.time = step.data.time;
      slot.pictures.assign(step.orbits.begin(), step.orbits.end());  // references, not pixels
    });
  }
  OutputTally tally() const override { return jobs_.tally(); }

 private:
  struct Slot {
    std::int64_t step = 0;
    double time = 0;
    std::vector<OrbitPicture> pictures;
  };

  // On the writer's thread: the step's files, then the catalogue with their rows.
  void run(Slot& slot) {
    const std::string folder = step_folder(slot.step);
    std::filesystem::create_directories(folder_ / folder);
    for (const OrbitPicture& p : slot.pictures) {
      const std::string name =
          view_names_[p.view] + "_p" + std::to_string(p.phi) + "_t" + std::to_string(p.theta);
      const std::string png = folder + "/" + name + ".png";
      write_png(folder_ / png, *p.picture.srgb8(), sync_);
      std::string exr;
      if (depth_ && p.depth) {
        exr = folder + "/" + name + ".exr";
        write_exr_channel(folder_ / exr, *p.depth, "Z", sync_);
      }
      rows_ << slot.time << "," << slot.step << "," << view_names_[p.view] << "," << p.phi << ","
            << p.theta << "," << png << (depth_ ? "," + exr : "") << "\n";
    }
    slot.pictures.clear();  // the buffers back to their views
    write_file_atomically(folder_ / "data.csv", rows_.str(), sync_);
  }

  static std::string step_folder(std::int64_t step) {
    std::string name = std::to_string(step);
    return std::string(name.size() < 8 ? 8 - name.size() : 0, '0') + name;
  }

  std::filesystem::path folder_;
  std::vector<std::string> view_names_;
  bool depth_;
  bool sync_;
  std::ostringstream rows_;  // the writer thread's only
  PooledJobs<Slot> jobs_;
};

}  // namespace

OutputKind cinema_output_kind() {
  OutputKind k = output_kind<CinemaSettings, CinemaOutput>(
      "cinema", "Cinema steps", cinema_section(), {.picture = true}, false, true);
  k.orbits = [](const OutputSettings& settings) {
    const auto& s = dynamic_cast<const CinemaSettings&>(settings);
    return OrbitRequest{s.views, s.phi, s.theta, s.depth};
  };
  return k;
}

}  // namespace voxspan
