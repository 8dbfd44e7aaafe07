// insitu/config/config.h - what the runtime does, as typed settings loaded from YAML.
//
// The simulation describes its data once (the adapter's views); this file says what to do with
// it: which views to render and how, when, and which files to write where. Loading checks
// everything against the schema (insitu/config/schema.h; docs/runtime.md lists every key, type
// and default): unknown keys, wrong types and bad values are errors naming the key path, the
// file and the line, all reported at once, at start-up. Every key has a default, so an empty
// file works.
//
// The views and outputs are kinds that plug in (insitu/config/settings.h); the functions here
// take the list of kinds, and insitu/runtime/config_file.h calls them with the registered ones.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/condition.h"
#include "insitu/config/settings.h"
#include "insitu/config/trigger.h"
#include "render/gl/context.h"
#include "render/surface_renderer.h"

namespace voxspan {

enum class QueuePolicy { wait, drop };
inline constexpr EnumName<QueuePolicy> kQueuePolicyNames[] = {{"wait", QueuePolicy::wait},
                                                              {"drop", QueuePolicy::drop}};

// How the ranks of an MPI job composite their span images (insitu/views/span_compositor.h).
enum class CompositeScheme { direct_send, root };
inline constexpr EnumName<CompositeScheme> kCompositeSchemeNames[] = {
    {"direct_send", CompositeScheme::direct_send}, {"root", CompositeScheme::root}};

struct RendererConfig {
  RenderBackend backend = RenderBackend::automatic;
  gl::Platform platform = gl::Platform::automatic;
  bool debug = false;
  double gpu_memory_mib = 512;  // budget for the tiled bit grid and span buffers
  // The GPU (EGL device) of this process; nullopt: the node-local MPI rank's, modulo devices.
  std::optional<std::int64_t> gpu_device;
  CompositeScheme composite = CompositeScheme::direct_send;
  ReadLater readback = ReadLater::on_gpu;  // when the GL renderer's pictures are read later
  // Host memory the views may take, checked at start-up by estimate; nullopt: half of the
  // machine's.
  std::optional<double> host_memory_mib;
  bool operator==(const RendererConfig&) const = default;
};

struct ClassificationConfig {
  std::optional<std::int64_t> full_count;  // particles in a full cell; nullopt = from spacing
  std::optional<double> particle_spacing;  // world units; nullopt = as the solver reports it
  bool validate_grid = false;              // check each particle lies in the cell the grid says
  bool operator==(const ClassificationConfig&) const = default;
};

struct WriterConfig {
  int queue_size = 8;  // jobs waiting for the writer thread
  QueuePolicy when_full = QueuePolicy::wait;
  bool fsync = true;  // make files durable before they get their final name
  bool operator==(const WriterConfig&) const = default;
};

// The live page (insitu/live/live_server.h): served from rank 0 while the job runs.
struct LiveConfig {
  bool enabled = false;
  std::string address = "127.0.0.1";  // a non-local one needs `token`
  int port = 0;                       // 0: a free port, chosen at start and printed
  std::string token;                  // empty: a random one made at start and printed
  double linger_seconds = 0;          // the final page kept up after the last step
  bool interactive = false;           // the page may turn the views' cameras (POST /camera)
  bool operator==(const LiveConfig&) const = default;
};
// True for the loopback addresses (127.0.0.0/8, `localhost`), which only this machine
// reaches.
bool is_local_address(std::string_view address);

// A view or an output of the config: its kind's name and its settings.
template <class Base> struct Configured {
  std::string kind;
  Cloned<Base> settings;
  bool operator==(const Configured&) const = default;
};
using ConfiguredView = Configured<ViewSettings>;
using ConfiguredOutput = Configured<OutputSettings>;

struct Config {
  std::string output_folder = "voxspan-output";
  std::string log_level;                      // empty: keep the logger's level (VOXSPAN_LOG_LEVEL)
  TriggerSpec trigger{10, 0, true, true};     // render steps
  std::map<std::string, double> constants;    // names the triggers' conditions may use
  std::map<std::string, ConditionBox> boxes;  // boxes their reductions may be over
  std::vector<ConfiguredView> views;          // default_config(): one view "main" of the first kind
  RendererConfig renderer;
  ClassificationConfig classification;
  std::vector<ConfiguredOutput> outputs;  // every output kind, in the kinds' order
  WriterConfig writer;
  LiveConfig live;
  bool operator==(const Config&) const = default;

  // An output's folder: absolute as given, else under output_folder.
  std::filesystem::path folder_of(const OutputSettings& output) const;
  // The settings of output kind `kind`; throws voxspan::Error when there is none.
  OutputSettings& output(std::string_view kind);
  const OutputSettings& output(std::string_view kind) const;
  // The settings of the output whose settings type is S; throws when there is none.
  template <class S> S& output();
  template <class S> const S& output() const;
  // The position of output `kind` in `outputs`; throws voxspan::Error when there is none.
  std::size_t output_index(std::string_view kind) const;
  // The particle attributes the enabled outputs ask for, each once.
  std::vector<std::string> output_attributes() const;
};

struct ConfigKinds {
  std::vector<ViewConfigKind> views;  // the first is the kind of a view that names none
  std::vector<OutputConfigKind> outputs;
};

// Every key at its default: one view "main" of the first view kind, every output kind's
// defaults.
Config default_config(const ConfigKinds& kinds);
// Throws voxspan::Error listing every problem ("<source>:<line>:<col>: <key path>: ...").
Config read_config(std::string_view yaml, std::string_view source_name, const ConfigKinds& kinds);
// The effective configuration as YAML (every key, defaults included); reading it again gives
// the same Config.
std::string write_config(const Config& config, const ConfigKinds& kinds);
// Every value of the config as "<key path>: <value>" lines, in order ("views[0].width: 640"):
// what two processes compare to tell whether they read the same config.
std::vector<std::string> config_lines(const Config& config, const ConfigKinds& kinds);
// Markdown: a table per section, the views' and outputs' kinds included (docs/runtime.md).
std::string config_reference(const ConfigKinds& kinds);

template <class S> S& Config::output() {
  for (ConfiguredOutput& o : outputs)
    if (S* s = dynamic_cast<S*>(&*o.settings)) return *s;
  return dynamic_cast<S&>(output("(no output of this settings type)"));
}

template <class S> const S& Config::output() const {
  return const_cast<Config&>(*this).output<S>();
}

}  // namespace voxspan
