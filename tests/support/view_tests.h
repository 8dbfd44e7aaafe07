// What the view kinds' tests through the runtime share (tests only): a block of particles with
// one attribute, the config of a run with one view, the adapter options of a spacing, the view's
// latest result, the reading of its keys and the check that bad ones are refused with their
// line.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "insitu/runtime/config_file.h"
#include "insitu/runtime/pipeline.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"

namespace voxspan::test {

// 20 x 10 x 10 particles of `spacing` from the origin (1.0 x 0.5 x 0.5 at 0.05), their scalar
// `name` given by value(i, x) of their column i along x and their x.
struct ParticleBlock {
  double spacing;
  std::string name;
  std::vector<double> xyz, values;

  ParticleBlock(double s, std::string attribute, const std::function<double(int, double)>& value)
      : spacing(s), name(std::move(attribute)) {
    for (int k = 0; k < 10; ++k)
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 20; ++i) {
          for (int a : {i, j, k}) xyz.push_back((a + 0.5) * spacing);
          values.push_back(value(i, xyz[xyz.size() - 3]));
        }
  }
  ParticleView view() const {
    return ParticleView::aos(xyz.data(), values.size()).with_scalar(name.c_str(), values.data());
  }
};

// A run that renders one view, `view` (the inside of its flow map: "name: v, kind: ..."), every
// step, into `folder` under the tests' temporary folder, writing no files.
inline std::string one_view_config(const std::string& folder, const std::string& view) {
  return "output_folder: " + testing::TempDir() + folder +
         "\n"
         "outputs: {png: {enabled: false}, stats: {enabled: false}}\n"
         "trigger: {every_steps: 1}\n"
         "views:\n  - {" +
         view + "}\n";
}

inline AdapterOptions spaced(double spacing) {
  AdapterOptions o;
  o.classify.particle_spacing = spacing;
  return o;
}

inline const ViewResult& latest_view(const Adapter& a) {
  return dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
}

// The first step of a run of `config` over `b`, and its status.
inline Status first_step(const std::string& config, const ParticleBlock& b) {
  Adapter a = adapter_from_config_text(config, spaced(b.spacing));
  return a.execute(0, 0, b.view());
}

// The first step of a run of `config` over `b` fails on `key` (with its config line: "<config>:5:5:
// views[0].quantity"), whose value `asked` `b` does not pass, naming the attribute it passes.
inline void expect_missing_attribute(const std::string& config, const ParticleBlock& b,
                                     const std::string& key, const std::string& asked) {
  const Status s = first_step(config, b);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find(key + " \"" + asked + "\""), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("(it passes: " + b.name + ")"), std::string::npos) << s.message;
}

// The picture of the first step of a run of `config` over `b` (a failed step fails the test).
inline FloatImage first_picture(const std::string& config, const ParticleBlock& b) {
  Adapter a = adapter_from_config_text(config, spaced(b.spacing));
  const Status s = a.execute(0, 0, b.view());
  EXPECT_TRUE(s.ok()) << s.message;
  return s.ok() ? *latest_view(a).picture : FloatImage();
}

// The settings of the one view of kind S that `keys` (the inside of its flow map) configure,
// checked to read back the same from the YAML they write.
template <class S> S read_view(const std::string& keys) {
  const Config c = load_config_string("views:\n  - {" + keys + "}\n");
  EXPECT_EQ(load_config_string(to_yaml(c)).views[0], c.views[0]) << keys;
  return dynamic_cast<const S&>(*c.views[0].settings);
}

// Each {keys, words}: a view of `kind` with `keys` is refused, its message naming line 2 of the
// config and holding `words`.
inline void expect_refused_with_line(
    const std::string& kind, const std::vector<std::pair<std::string, std::string>>& cases) {
  for (const auto& [keys, words] : cases) {
    try {
      load_config_string("views:\n  - {kind: " + kind + ", " + keys + "}\n", "v.yaml");
      ADD_FAILURE() << keys << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("v.yaml:2:"), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << keys << ": " << what;
    }
  }
}

}  // namespace voxspan::test
