// insitu/outputs/kinds/view_images.h - the outputs that write one image per view and step (PNG
// pictures, EXR depth images): each view's picture referenced (insitu/views/shared_picture.h),
// another image copied, into a pooled slot on the solver's thread (no allocation once the slots
// have held the largest view), written as
// <folder>/<view>_<step>.<extension> on the writer's. Such a kind is its settings, its schema
// section and a ViewImageFormat (depth_output.cpp), or its own Output on ViewImageJobs
// (png_output.cpp, whose encoder takes a setting).
#pragma once

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {

class ViewImageJobs {
 public:
  // Writes the kept image (a picture readable as floats or as 8-bit sRGB: KeptImage) to a file.
  using Write = std::function<void(const std::filesystem::path&, KeptImage&)>;

  ViewImageJobs(const OutputContext& c, std::string extension, const char* label, Write write)
      : folder_(c.folder),
        view_names_(c.view_names.begin(), c.view_names.end()),
        extension_(std::move(extension)),
        label_(label),
        largest_(largest_view_floats(c.config)),
        write_(std::move(write)),
        jobs_(c.writer, c.slots, [this](Slot& s) { run(s); }) {}

  // Hands over each view's `product` (ViewResult::picture or ::first_hit_depth); views without
  // one (failed, or not asked) are skipped.
  void submit(const OutputStep& step, const FloatImage* ViewResult::*product) {
    for (std::size_t v = 0; v < step.views.size(); ++v) {
      const FloatImage* image = step.views[v].*product;
      if (image == nullptr) continue;
      jobs_.submit(label_, [&](Slot& s) {
        s.view = v;
        s.step = step.data.step;
        // a pooled slot serves every view
        s.image.keep(*image, step.views[v].shared_picture, largest_);
      });
    }
  }

  OutputTally tally() const { return jobs_.tally(); }

 private:
  struct Slot {
    KeptImage image;
    std::size_t view = 0;
    std::int64_t step = 0;
  };

  static std::size_t largest_view_floats(const Config& config) {
    std::size_t most = 0;
    for (const ConfiguredView& v : config.views)
      most = std::max(most, 4 * std::size_t(v.settings->width) * std::size_t(v.settings->height));
    return most;
  }

  void run(Slot& s) const {
    write_(folder_ / step_file_name(view_names_[s.view], s.step, extension_), s.image);
    s.image.release();  // the picture's buffer back to its view as soon as it is written
  }

  std::filesystem::path folder_;
  std::vector<std::string> view_names_;
  std::string extension_;
  const char* label_;
  std::size_t largest_;
  Write write_;
  PooledJobs<Slot> jobs_;
};

// What a per-view image output writes, and how.
struct ViewImageFormat {
  const char* extension;                   // "png"
  const char* label;                       // the writer's name for a job: "PNG frame"
  const FloatImage* ViewResult::*product;  // &ViewResult::picture
  ViewNeeds needs;                         // what the views must make for it
  void (*write)(const std::filesystem::path& path, const FloatImage& image, bool sync);
};

class ViewImageOutput final : public Output {
 public:
  ViewImageOutput(const ViewImageFormat& format, const OutputContext& c)
      : product_(format.product),
        jobs_(c, format.extension, format.label,
              [write = format.write, sync = c.fsync](const std::filesystem::path& path,
                                                     KeptImage& image) {
                write(path, image.image(), sync);
              }) {}
  void write(const OutputStep& step) override { jobs_.submit(step, product_); }
  OutputTally tally() const override { return jobs_.tally(); }

 private:
  const FloatImage* ViewResult::*product_;
  ViewImageJobs jobs_;
};

// The kind of a per-view image output whose settings type S is read by `section`.
template <class S>
OutputKind view_image_output_kind(std::string_view name, std::string_view noun,
                                  const schema::Section<S>& section, ViewImageFormat format) {
  return {config_kind<OutputSettings>(name, section),
          noun,
          format.needs,
          false,
          true,
          [format](const OutputSettings&, const OutputContext& c) -> std::unique_ptr<Output> {
            return std::make_unique<ViewImageOutput>(format, c);
          }};
}

}  // namespace voxspan
