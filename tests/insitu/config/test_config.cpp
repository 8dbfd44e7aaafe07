// The YAML config: defaults, every section, and errors that name the key path and the line.
#include <gtest/gtest.h>

#include <fstream>

#include "insitu/outputs/kinds/vdb_output.h"
#include "insitu/outputs/kinds/vtk_output.h"
#include "insitu/runtime/config_file.h"
#include "insitu/views/surface_view.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_folder.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

SurfaceSettings& view(Config& c, std::size_t i) {
  return dynamic_cast<SurfaceSettings&>(*c.views.at(i).settings);
}

// The message of the Error the YAML raises ("" when it loads).
std::string error_of(const std::string& yaml) {
  return test::error_message([&] { load_config_string(yaml, "test.yaml"); });
}

TEST(Config, EmptyFileGivesTheDefaults) {
  Config c = load_config_string("", "empty.yaml");
  EXPECT_EQ(c, default_config());
  ASSERT_EQ(c.views.size(), 1u);
  EXPECT_EQ(c.views[0].kind, "surface");
  EXPECT_EQ(view(c, 0).name, "main");
  EXPECT_EQ(view(c, 0).width, 960);
  EXPECT_EQ(view(c, 0).height, 540);
  EXPECT_EQ(view(c, 0).shading, ShadeMode::translucent);
  EXPECT_TRUE(view(c, 0).camera.automatic);
  EXPECT_EQ(view(c, 0).max_layers, 16384);
  EXPECT_DOUBLE_EQ(view(c, 0).alpha_degrees, 14);
  EXPECT_EQ(c.trigger, (TriggerSpec{10, 0, true, true}));
  EXPECT_TRUE(c.output("png").enabled);
  EXPECT_TRUE(c.output("stats").enabled);
  EXPECT_FALSE(c.output("vdb").enabled);
  EXPECT_FALSE(c.output("vtk").enabled);
  EXPECT_EQ(c.writer.when_full, QueuePolicy::wait);
  // A comment-only file is empty too.
  EXPECT_EQ(load_config_string("# nothing here\n"), default_config());
}

TEST(Config, ReadsEverySection) {
  Config c = load_config_string(R"(
output_folder: /tmp/run42
log_level: info
trigger: {every_steps: 5, every_time: 0.25, first: false, last: true}
views:
  - name: side
    width: 640
    height: 360
    shading: refractive
    deep_ao: true
    camera: {eye: [3, -4, 2], target: [0.5, 0.5, 0.2], up: [0, 0, 1], fov: 35}
    layer_angle: 7
    gap: 0.01
    max_spans: 7
    filter_radius: 0.02
    max_layers: 4096
    absorption: [0.5, 0.2, 0.1]
    ior: 1.5
    bounces: 4
    ground_height: -0.25
    ground_tile: 0.5
    ground_light: [0.9, 0.9, 0.9]
    ground_dark: [0.1, 0.1, 0.2]
    sky_zenith: [0, 0, 0.5]
    sky_horizon: [1, 1, 1]
  - name: top
    shading: opaque
    camera: {direction: [0, 0, -1], up: [0, 1, 0], margin: 1.2}
renderer: {gl_platform: surfaceless, debug: true, gpu_memory_mib: 128}
classification: {full_count: 10, particle_spacing: 0.005, validate_grid: true}
outputs:
  png: {folder: pictures}
  stats: {enabled: false}
  vdb:
    enabled: true
    folder: /scratch/snap
    trigger: {every_time: 1.0}
    voxel_size: 0.002
    half_width: 4
    closing: 0
    fill_inner: false
    cell_states: false
    attributes: [velocity, pressure]
  vtk: {enabled: true, cells: false, attributes: [density]}
writer: {queue_size: 3, when_full: drop, fsync: false}
)");
  EXPECT_EQ(c.output_folder, "/tmp/run42");
  EXPECT_EQ(c.log_level, "info");
  EXPECT_EQ(c.trigger, (TriggerSpec{5, 0.25, false, true}));
  ASSERT_EQ(c.views.size(), 2u);
  const SurfaceSettings& side = view(c, 0);
  EXPECT_EQ(side.name, "side");
  EXPECT_EQ(side.width, 640);
  EXPECT_EQ(side.shading, ShadeMode::refractive);
  EXPECT_TRUE(side.deep_ao);
  EXPECT_FALSE(side.camera.automatic);
  EXPECT_EQ(side.camera.eye, (Vec3d{3, -4, 2}));
  EXPECT_EQ(side.camera.target, (Vec3d{0.5, 0.5, 0.2}));
  EXPECT_DOUBLE_EQ(side.camera.fov_degrees, 35);
  EXPECT_DOUBLE_EQ(side.alpha_degrees, 7);
  EXPECT_EQ(side.gap, 0.01);
  EXPECT_EQ(side.max_spans, 7);
  EXPECT_EQ(side.filter_radius, 0.02);
  EXPECT_EQ(side.max_layers, 4096);
  EXPECT_EQ(side.absorption, (Vec3d{0.5, 0.2, 0.1}));
  EXPECT_DOUBLE_EQ(side.ior, 1.5);
  EXPECT_EQ(side.bounces, 4);
  EXPECT_EQ(side.ground_height, -0.25);
  EXPECT_EQ(side.ground_tile, 0.5);
  EXPECT_EQ(side.ground_light, (Vec3d{0.9, 0.9, 0.9}));
  EXPECT_EQ(side.ground_dark, (Vec3d{0.1, 0.1, 0.2}));
  EXPECT_EQ(side.sky_zenith, (Vec3d{0, 0, 0.5}));
  EXPECT_EQ(side.sky_horizon, (Vec3d{1, 1, 1}));
  const SurfaceSettings& top = view(c, 1);
  EXPECT_EQ(top.shading, ShadeMode::opaque);
  EXPECT_TRUE(top.camera.automatic);
  EXPECT_EQ(top.camera.direction, (Vec3d{0, 0, -1}));
  EXPECT_DOUBLE_EQ(top.camera.margin, 1.2);
  EXPECT_FALSE(top.gap.has_value());  // auto
  EXPECT_FALSE(top.absorption.has_value());
  EXPECT_FALSE(top.ground_height.has_value());
  EXPECT_EQ(c.renderer.platform, gl::Platform::surfaceless);
  EXPECT_TRUE(c.renderer.debug);
  EXPECT_DOUBLE_EQ(c.renderer.gpu_memory_mib, 128);
  EXPECT_EQ(c.classification.full_count, 10);
  EXPECT_EQ(c.classification.particle_spacing, 0.005);
  EXPECT_TRUE(c.classification.validate_grid);
  EXPECT_EQ(c.output("png").folder, "pictures");
  EXPECT_FALSE(c.output("stats").enabled);
  const VdbSettings& vdb = c.output<VdbSettings>();
  EXPECT_TRUE(vdb.enabled);
  EXPECT_EQ(vdb.trigger, (TriggerSpec{0, 1.0, false, false}));
  EXPECT_EQ(vdb.snapshot.voxel_size, 0.002);
  EXPECT_EQ(vdb.snapshot.half_width, 4);
  EXPECT_EQ(vdb.snapshot.closing, 0.0);
  EXPECT_FALSE(vdb.snapshot.fill_inner);
  EXPECT_FALSE(vdb.snapshot.cell_states);
  EXPECT_EQ(vdb.attributes, (std::vector<std::string>{"velocity", "pressure"}));
  EXPECT_TRUE(c.output<VtkSettings>().particles);
  EXPECT_FALSE(c.output<VtkSettings>().cells);
  EXPECT_EQ(c.writer.queue_size, 3);
  EXPECT_EQ(c.writer.when_full, QueuePolicy::drop);
  EXPECT_FALSE(c.writer.fsync);
  EXPECT_EQ(c.folder_of(c.output("png")), std::filesystem::path("/tmp/run42/pictures"));
  EXPECT_EQ(c.folder_of(c.output("vdb")), std::filesystem::path("/scratch/snap"));
}

TEST(Config, PngAndStatsFollowTheRenderTriggerUnlessGiven) {
  Config c = load_config_string(R"(
trigger: {every_steps: 7}
outputs:
  stats: {trigger: {every_steps: 1}}
)");
  EXPECT_EQ(c.output("png").trigger, (TriggerSpec{7, 0, false, false}));
  EXPECT_EQ(c.output("stats").trigger, (TriggerSpec{1, 0, false, false}));
}

TEST(Config, UnknownKeyNamesThePathTheLineAndTheNearestKey) {
  std::string e = error_of("views:\n  - name: a\n    camera:\n      fvo: 30\n");
  EXPECT_NE(e.find("test.yaml:4:7: views[0].camera.fvo: unknown key (did you mean 'fov'?)"),
            std::string::npos)
      << e;
  e = error_of("outputs:\n  png: {enabled: true}\n  pngs: {}\n");
  EXPECT_NE(e.find("test.yaml:3:3: outputs.pngs: unknown key"), std::string::npos) << e;
  e = error_of("render_every: 10\n");
  EXPECT_NE(e.find("test.yaml:1:1: render_every: unknown key"), std::string::npos) << e;
}

// A mistake in the top-level trigger is one error, on its line: not also one for every output
// that follows the render trigger (they were, without a line).
TEST(Config, ATriggerMistakeIsOneErrorWithItsLine) {
  std::string e = error_of("trigger:\n  evry_steps: 10\n");
  EXPECT_NE(e.find("invalid configuration: test.yaml:2:3: trigger.evry_steps: unknown key (did "
                   "you mean 'every_steps'?)"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find("never fires"), std::string::npos) << e;
  e = error_of("views: []\ntrigger: {first: false, last: false, every_steps: 0}\n");
  EXPECT_NE(e.find("invalid configuration: test.yaml:2:10: trigger: never fires"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find("outputs."), std::string::npos) << e;
}

// The live page listens where only this machine reaches it unless told otherwise; an address
// others reach needs a token of the user's own.
TEST(Config, TheLivePageNeedsATokenOnAnAddressOthersReach) {
  const Config c = load_config_string("live: {enabled: true}\n", "test.yaml");
  EXPECT_EQ(c.live.address, "127.0.0.1");
  EXPECT_TRUE(c.live.token.empty());
  EXPECT_EQ(c.live.port, 0);
  std::string e = error_of("live:\n  enabled: true\n  address: 0.0.0.0\n");
  EXPECT_NE(e.find("test.yaml:3:12: live.address: 0.0.0.0 is reachable from other machines: "
                   "give a `live.token`"),
            std::string::npos)
      << e;
  EXPECT_EQ(error_of("live: {enabled: true, address: 0.0.0.0, token: abcdefghijklmnop12}\n"), "");
  e = error_of("live: {enabled: true, address: \"::1\"}\n");
  EXPECT_NE(e.find("live.address: expected an IPv4 address"), std::string::npos) << e;
  EXPECT_EQ(error_of("live: {enabled: true, address: localhost}\n"), "");
  e = error_of("live: {address: 0.0.0.0, token: short}\n");
  EXPECT_NE(e.find("live.token: expected 16 or more letters"), std::string::npos) << e;
  e = error_of("live: {address: example.org}\n");
  EXPECT_NE(e.find("live.address: expected an IPv4 address"), std::string::npos) << e;
  EXPECT_TRUE(is_local_address("127.0.0.2"));
  EXPECT_FALSE(is_local_address("10.0.0.1"));
  EXPECT_FALSE(is_local_address("::"));
}

TEST(Config, WrongTypesAndBadValuesNameKeyAndLine) {
  struct Case {
    const char* yaml;
    const char* expected;
  };
  const Case cases[] = {
      {"views:\n  - width: wide\n",
       "test.yaml:2:12: views[0].width: expected an integer from 1 to 16384; got \"wide\""},
      {"views:\n  - width: 0\n", "views[0].width: expected an integer from 1 to 16384; got \"0\""},
      {"views:\n  - width: 2.5\n", "views[0].width: expected an integer"},
      {"views:\n  - shading: glass\n",
       "test.yaml:2:14: views[0].shading: expected one of opaque, translucent, refractive; got "
       "\"glass\""},
      {"views:\n  - max_layers: 100\n", "views[0].max_layers: must be a multiple of 32"},
      {"views:\n  - {kind: slice, quantity: p, scale: log, range: [0, 1]}\n",
       "views[0].range: a `log` scale needs a range above 0; got [0, 1]"},
      {"views:\n  - {kind: volume, scale: logarithmic}\n",
       "views[0].scale: expected one of linear, log; got \"logarithmic\""},
      {"views:\n  - layer_angle: 0\n", "views[0].layer_angle: expected a number in (0, 45]"},
      {"views:\n  - alpha: 7\n", "views[0].alpha: was renamed 'layer_angle'"},
      {"views:\n  - camera: {fov: 180}\n", "views[0].camera.fov: expected a number in (0, 179]"},
      {"views:\n  - camera: {eye: [1, 2]}\n",
       "views[0].camera.eye: expected three numbers [x, y, z]"},
      {"views:\n  - camera: {eye: [1, 2, 3]}\n",
       "views[0].camera: a manual camera needs both eye and target"},
      {"views:\n  - camera: {eye: [1, 2, 3], target: [1, 2, 3]}\n",
       "views[0].camera.target: must differ from camera.eye"},
      {"views:\n  - camera: {eye: [0, 0, 5], target: [0, 0, 0]}\n",
       "views[0].camera.up: must not be parallel to the viewing direction"},
      {"views:\n  - camera: {auto: true, eye: [0, 0, 5]}\n",
       "views[0].camera.eye: automatic framing (auto: true)"},
      {"views:\n  - camera: {direction: [0, 0, 1]}\n",
       "views[0].camera.direction: must not be parallel to camera.up"},
      {"views:\n  - name: a/b\n", "views[0].name: must be letters, digits"},
      {"views:\n  - name: a\n  - name: a\n", "views[1].name: \"a\" names two views"},
      {"views:\n  - gap: -1\n", "views[0].gap: expected a number of at least 0"},
      {"views:\n  - ground_tile: 0\n", "views[0].ground_tile: expected a number above 0"},
      {"views:\n  - ground_dark: [0, -1, 0]\n",
       "views[0].ground_dark: a colour must not be negative"},
      {"views:\n  - absorption: clear\n", "views[0].absorption: expected three numbers"},
      {"views: main\n", "views: expected a list of views"},
      {"trigger: {every_steps: -3}\n", "trigger.every_steps: expected an integer from 0"},
      {"trigger: {first: maybe}\n", "trigger.first: expected true or false; got \"maybe\""},
      {"trigger: 10\n", "trigger: expected a map of settings; got \"10\""},
      {"renderer: {gl_platform: vulkan}\n",
       "renderer.gl_platform: expected one of auto, nvidia, device, surfaceless; got \"vulkan\""},
      {"renderer: {gpu_memory_mib: 0}\n", "renderer.gpu_memory_mib: expected a number in [1,"},
      {"classification: {full_count: 0}\n",
       "classification.full_count: expected an integer from 1"},
      {"writer: {when_full: sometimes}\n",
       "writer.when_full: expected one of wait, drop; got \"sometimes\""},
      {"writer: {queue_size: 0}\n", "writer.queue_size: expected an integer from 1 to 4096"},
      {"log_level: loud\n", "log_level: expected one of error, warning, info, debug"},
      {"output_folder: ''\n", "output_folder: must not be empty"},
      {"outputs: {stats: {file: a/b.jsonl}}\n", "outputs.stats.file: must be a plain file name"},
      {"outputs: {vdb: {enabled: true, trigger: {}}}\n",
       "outputs.vdb.trigger: never fires while the output is enabled"},
      {"outputs: {vdb: {voxel_size: 0}}\n", "outputs.vdb.voxel_size: expected a number above 0"},
      {"outputs: {vdb: {attributes: [v, v]}}\n", "outputs.vdb.attributes: \"v\" given twice"},
      {"outputs: {vtk: {enabled: true, particles: false, cells: false}}\n",
       "outputs.vtk: enabled but writes nothing"},
      {"views:\n  - {kind: volume, opacity: [0.1, 0.5]}\n",
       "views[0].opacity: expected a list of [a, b] pairs of numbers; got [0.1, 0.5], whose item "
       "1 is \"0.1\""},
      {"outputs: {cinema: {phi: [0, 200]}}\n",
       "outputs.cinema.phi: expected a list of integers in [-180, 180]; got [0, 200], whose item 2 "
       "is \"200\""},
      {"views: [\n", "test.yaml:2:1: (top level): not valid YAML"},
  };
  for (const Case& c : cases) {
    std::string e = error_of(c.yaml);
    EXPECT_NE(e.find(c.expected), std::string::npos) << "yaml:\n" << c.yaml << "error: " << e;
  }
}

TEST(Config, ReportsEveryErrorAtOnce) {
  std::string e =
      error_of("bogus: 1\nviews:\n  - width: -1\n    height: x\nwriter: {when_full: no}\n");
  EXPECT_NE(e.find("4 errors"), std::string::npos) << e;
  EXPECT_NE(e.find("bogus"), std::string::npos);
  EXPECT_NE(e.find("views[0].width"), std::string::npos);
  EXPECT_NE(e.find("views[0].height"), std::string::npos);
  EXPECT_NE(e.find("writer.when_full"), std::string::npos);
}

TEST(Config, DuplicateKeysAreErrors) {
  std::string e = error_of("output_folder: a\noutput_folder: b\n");
  EXPECT_NE(e.find("test.yaml:2:1: output_folder: given twice"), std::string::npos) << e;
}

TEST(Config, EmittedYamlLoadsBackToTheSameConfig) {
  Config c = default_config();
  EXPECT_EQ(load_config_string(to_yaml(c)), c);
  c.output_folder = "out dir";
  c.log_level = "debug";
  c.trigger = {3, 0.125, false, true};
  view(c, 0).camera.automatic = false;
  view(c, 0).camera.eye = {1, 2, 3};
  view(c, 0).camera.target = {0.1, 0.2, 0.3};
  view(c, 0).gap = 0.0123456789012345;
  c.views.push_back(c.views[0]);
  view(c, 1).name = "second";
  view(c, 1).camera = CameraConfig{};
  view(c, 1).shading = ShadeMode::refractive;
  c.classification.full_count = 9;
  c.output<VdbSettings>().enabled = true;
  c.output<VdbSettings>().attributes = {"velocity"};
  c.output("vtk").enabled = true;
  c.output("depth").enabled = true;
  c.writer.when_full = QueuePolicy::drop;
  std::string yaml = to_yaml(c);
  EXPECT_EQ(load_config_string(yaml), c) << yaml;
}

TEST(Config, LoadsFilesAndNamesThemInErrors) {
  test::TempFolder dir;
  std::ofstream(dir / "good.yaml") << "views:\n  - width: 320\n";
  EXPECT_EQ(load_config_file(dir / "good.yaml").views[0].settings->width, 320);
  std::ofstream(dir / "bad.yaml") << "\n\nwriter: {queue: 3}\n";
  try {
    load_config_file(dir / "bad.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "bad.yaml").string() + ":3:10: writer.queue"),
              std::string::npos)
        << e.what();
  }
  try {
    load_config_file(dir / "missing.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.yaml: No such file"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace voxspan
