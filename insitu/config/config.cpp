// The config schema of the top level, the renderer, classification, the writer and the live
// page; a trigger's keys are in trigger.cpp, a camera's in camera_section.cpp, the views' and
// outputs' own from their kinds (insitu/views/, insitu/outputs/). The mechanism is
// insitu/config/schema.h.
#include "insitu/config/config.h"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "insitu/config/yaml_reader.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

using schema::Key;
using schema::Section;
using yaml::Checker;
using yaml::MapReader;

const Section<RendererConfig>& renderer_section() {
  using R = RendererConfig;
  static const Section<R> s{
      "renderer",
      {schema::choice("backend", &R::backend, kRenderBackendNames,
                      "the GL renderer (`gl`, llvmpipe included) or the CPU one (`cpu`); `auto` "
                      "= GL on a GPU or on the `gl_platform` named, else the CPU renderer "
                      "(render/backend.h)"),
       schema::choice("gl_platform", &R::platform, gl::kPlatformNames,
                      "as `VOXSPAN_GL_PLATFORM` (which overrides it)"),
       schema::flag("debug", &R::debug, "GL debug context"),
       schema::number("gpu_memory_mib", &R::gpu_memory_mib, schema::between(1, 1 << 24),
                      "budget for the tiled bit grid and span buffers"),
       schema::integer_or_auto("gpu_device", &R::gpu_device, 0, 1023,
                               "the EGL device (GPU) of this process; `auto` = in an MPI job the "
                               "node-local rank's, modulo the devices (the first alone)"),
       schema::choice("composite", &R::composite, kCompositeSchemeNames,
                      "in an MPI job, how the ranks merge their span images: bands merged by "
                      "every rank (`direct_send`) or all on rank 0 (`root`); docs/design.md"),
       schema::choice("readback", &R::readback, kReadLaterNames,
                      "when the GL renderer's pictures are read back: `later` (the solver's "
                      "thread issues the read, a file's job waits for it), `wait` (at once), "
                      "`auto` = later on a GPU, at once on a software renderer (faster there); "
                      "pictures only PNG files and the live page take come as 8-bit sRGB made "
                      "on the GPU (4 bytes a pixel), except at once on a software renderer; "
                      "docs/design.md"),
       schema::number_or_auto("host_memory_mib", &R::host_memory_mib, schema::above(0),
                              "host memory the views may take, checked at start-up from their "
                              "sizes (about 96 bytes a pixel); `auto` = half of this machine's")}};
  return s;
}

const Section<ClassificationConfig>& classification_section() {
  using C = ClassificationConfig;
  static const Section<C> s{
      "classification",
      {schema::integer_or_auto("full_count", &C::full_count, 1, 1 << 20,
                               "particles in a full cell; `auto` = from the particle spacing"),
       schema::number_or_auto("particle_spacing", &C::particle_spacing, schema::above(0),
                              "world units; `auto` = as the solver reports it"),
       schema::flag("validate_grid", &C::validate_grid,
                    "check each particle lies in the cell the grid claims on every render step "
                    "(off: until one passes)")}};
  return s;
}

const Section<WriterConfig>& writer_section() {
  using W = WriterConfig;
  static const Section<W> s{
      "writer",
      {schema::integer("queue_size", &W::queue_size, 1, 4096,
                       "jobs waiting for the writer thread (each file of a step is one: with "
                       "`drop`, hold at least one step's files, or a step loses some)"),
       schema::choice(
           "when_full", &W::when_full, kQueuePolicyNames,
           "`wait` blocks the solver until a slot frees; `drop` skips the file and "
           "counts it (a warning at the 1st, 10th, 100th... drop, a summary at the end), "
           "except on the solver's last step, whose files finish() waits for anyway"),
       schema::flag("fsync", &W::fsync, "files are fsynced before they get their final name")}};
  return s;
}

// The token guards a page anyone on the network may reach: long enough not to be guessed, and
// plain enough to sit in a URL and a header as it is.
constexpr std::size_t kMinTokenLength = 16;

void check_live(MapReader& r, LiveConfig& c) {
  Checker& ch = r.checker();
  // IPv4 only: Debian's civetweb is built without IPv6.
  in_addr any{};
  if (inet_pton(AF_INET, c.address.c_str(), &any) != 1 && c.address != "localhost")
    ch.error(r.find("address"), r.path("address"),
             "expected an IPv4 address (0.0.0.0: every interface) or `localhost`; got \"" +
                 c.address + "\"");
  else if (c.enabled && !is_local_address(c.address) && c.token.empty())
    ch.error(r.find("address"), r.path("address"),
             c.address + " is reachable from other machines: give a `live.token` (" +
                 std::to_string(kMinTokenLength) + " or more letters and digits) or leave " +
                 "`address` at 127.0.0.1");
  const bool plain = std::all_of(c.token.begin(), c.token.end(), [](char k) {
    return std::isalnum(static_cast<unsigned char>(k)) || k == '-' || k == '_';
  });
  if (!c.token.empty() && (c.token.size() < kMinTokenLength || !plain))
    ch.error(r.find("token"), r.path("token"),
             "expected " + std::to_string(kMinTokenLength) +
                 " or more letters, digits, `-` or `_`; empty: a random one");
}

const Section<LiveConfig>& live_section() {
  using L = LiveConfig;
  static const Section<L> s{
      "live",
      {schema::flag("enabled", &L::enabled,
                    "serve the live page (rank 0): the latest pictures, the progress and the "
                    "in-situ cost per pass"),
       schema::text("address", &L::address,
                    "the IPv4 address it listens on; one outside 127.0.0.0/8 (not `localhost`) "
                    "needs `token`"),
       schema::integer("port", &L::port, 0, 65535, "0: a free port, printed with the URL"),
       schema::text("token", &L::token,
                    "what every request must carry; empty: a random one made at start and "
                    "printed once with the URL")
           .default_shown_as("random"),
       schema::number("linger_seconds", &L::linger_seconds, schema::between(0, 86400),
                      "the page stays up this long after the last step, saying the job ended "
                      "(the job waits)"),
       schema::flag("interactive", &L::interactive,
                    "the page may orbit, pan and zoom the views' cameras, from the next render "
                    "step on; never the solver")},
      check_live};
  return s;
}

// ---- views: a list, each item read by its kind's section

const ViewConfigKind* find_kind(const std::vector<ViewConfigKind>& kinds, std::string_view name) {
  for (const ViewConfigKind& k : kinds)
    if (k.name == name) return &k;
  return nullptr;
}

std::string kind_names(const std::vector<ViewConfigKind>& kinds) {
  std::string text;
  for (const ViewConfigKind& k : kinds) text += (text.empty() ? "" : ", ") + std::string(k.name);
  return text;
}

std::optional<ConfiguredView> read_view(Checker& checker, const YAML::Node& node,
                                        const std::string& path, std::size_t index,
                                        const std::vector<ViewConfigKind>& kinds) {
  const ViewConfigKind* kind = &kinds.front();
  if (node.IsMap() && node["kind"]) {
    const YAML::Node k = node["kind"];
    kind = k.IsScalar() ? find_kind(kinds, k.Scalar()) : nullptr;
    if (kind == nullptr) {
      checker.error(k, path + ".kind",
                    "expected one of " + kind_names(kinds) + "; got " + yaml::describe(k));
      return std::nullopt;
    }
  }
  ConfiguredView view{std::string(kind->name), kind->defaults()};
  ViewSettings& v = *view.settings;
  v.name = "view" + std::to_string(index);
  v.source.where = checker.where(node.Mark(), path);
  kind->read(checker, node, path, v);
  if (!schema::is_plain_name(v.name))
    checker.error(
        node.IsMap() && node["name"] ? node["name"] : node, path + ".name",
        "must be letters, digits, '_', '-' or '.' (it names files); got \"" + v.name + "\"");
  if (const std::string problem = caption_problem(v.caption); !problem.empty())
    checker.error(node.IsMap() && node["caption"] ? node["caption"] : node, path + ".caption",
                  problem);
  return view;
}

void read_views(MapReader& top, std::vector<ConfiguredView>& views,
                const std::vector<ViewConfigKind>& kinds) {
  if (!top.has("views")) return;
  const YAML::Node node = top.find("views");
  Checker& checker = top.checker();
  views.clear();
  if (node.IsNull()) return;
  if (!node.IsSequence()) {
    checker.error(node, "views",
                  "expected a list of views (\"- name: ...\"); got " + yaml::describe(node));
    return;
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string path = "views[" + std::to_string(i) + "]";
    std::optional<ConfiguredView> view = read_view(checker, node[i], path, i, kinds);
    if (!view) continue;
    if (!names.insert(view->settings->name).second)
      checker.error(node[i], path + ".name", "\"" + view->settings->name + "\" names two views");
    views.push_back(std::move(*view));
  }
}

// ---- outputs: a map of the output kinds, each read by its kind's section

void read_output(MapReader& outs, const OutputConfigKind& kind, const TriggerSpec& render_trigger,
                 OutputSettings& out) {
  const std::string name(kind.name);
  const YAML::Node node = outs.find(name);
  if (out.follows_render_trigger) out.trigger = render_trigger;
  if (node) out.source.where = outs.checker().where(node.Mark(), outs.path(name));
  kind.read(outs.checker(), node, outs.path(name), out);
  // An output on the render trigger that never fires is the top-level trigger's fault: said
  // there, once (read_outputs), not here for every output that follows it.
  const bool own_trigger = node.IsMap() && node["trigger"];
  if (out.enabled && out.trigger.never_fires() && (own_trigger || !out.follows_render_trigger)) {
    const YAML::Node trigger = node.IsMap() && node["trigger"] ? node["trigger"] : node;
    outs.checker().error(trigger, outs.path(name) + ".trigger",
                         "never fires while the output is enabled: set every_steps, "
                         "every_time, first, last or when, or enabled: false");
  }
  if (out.folder.empty())
    outs.checker().error(node, outs.path(name) + ".folder", "must not be empty");
}

void read_outputs(MapReader& top, Config& c, const std::vector<OutputConfigKind>& kinds) {
  std::vector<std::string_view> names;
  for (const OutputConfigKind& k : kinds) names.push_back(k.name);
  MapReader outs(top.checker(), top.find("outputs"), "outputs", names);
  for (std::size_t i = 0; i < kinds.size(); ++i)
    read_output(outs, kinds[i], c.trigger, *c.outputs[i].settings);
  // The render trigger's own mistake (an unknown key, a bad value) is its error already.
  if (!c.trigger.never_fires() || !top.has("trigger")) return;
  for (const std::string& e : top.checker().errors())
    if (e.find(": trigger.") != std::string::npos || e.find(": trigger:") != std::string::npos)
      return;
  top.checker().error(top.find("trigger"), "trigger",
                      "never fires: set every_steps, every_time, first, last or when");
}

// ---- the conditions' constants and boxes, and the conditions themselves

// Each entry of the map `key` of the top level, its name checked, handed to `read`.
void read_named(MapReader& top, const char* key,
                const std::function<void(const YAML::Node&, const std::string&)>& read) {
  if (!top.has(key)) return;
  const YAML::Node node = top.find(key);
  if (node.IsNull()) return;
  if (!node.IsMap()) {
    top.checker().error(node, key, "expected a map of names; got " + yaml::describe(node));
    return;
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string name = it->first.Scalar(), path = std::string(key) + "." + name;
    if (const std::string problem = name_problem(name); !problem.empty())
      top.checker().error(it->first, path, problem);
    else read(it->second, path);
  }
}

void read_constants(MapReader& top, Config& c) {
  c.constants.clear();
  read_named(top, "constants", [&](const YAML::Node& value, const std::string& path) {
    double v = 0;
    if (value.IsScalar() && YAML::convert<double>::decode(value, v) && std::isfinite(v))
      c.constants[path.substr(path.find('.') + 1)] = v;
    else top.checker().error(value, path, "expected a finite number; got " + yaml::describe(value));
  });
}

bool read_corner(const YAML::Node& node, std::array<double, 3>& p) {
  if (!node.IsSequence() || node.size() != 3) return false;
  for (std::size_t a = 0; a < 3; ++a)
    if (!node[a].IsScalar() || !YAML::convert<double>::decode(node[a], p[a]) || std::isnan(p[a]))
      return false;
  return true;
}

// YAML's own infinities, which read back.
void emit_corner(YAML::Emitter& e, const std::array<double, 3>& p) {
  e << YAML::BeginSeq;
  for (double v : p)
    if (std::isinf(v)) e << (v > 0 ? ".inf" : "-.inf");
    else schema::emit_value(e, v);
  e << YAML::EndSeq;
}

void read_boxes(MapReader& top, Config& c) {
  c.boxes.clear();
  read_named(top, "boxes", [&](const YAML::Node& value, const std::string& path) {
    ConditionBox b;
    bool ok = value.IsSequence() && value.size() == 2 && read_corner(value[0], b.lo) &&
              read_corner(value[1], b.hi);
    for (std::size_t a = 0; ok && a < 3; ++a) ok = b.lo[a] < b.hi[a];
    if (ok) c.boxes[path.substr(path.find('.') + 1)] = b;
    else
      top.checker().error(value, path,
                          "expected [[x0, y0, z0], [x1, y1, z1]] with x0 < x1, y0 < y1, z0 < z1");
  });
}

// A condition's mistake at its character, where `when` is one line (a block scalar's lines
// would need their indentation: there the line of `when` is said).
void check_condition(Checker& checker, const YAML::Node& when, const std::string& path,
                     const Config& c) {
  try {
    Condition(when.Scalar(), c.constants, c.boxes);
  } catch (const ConditionError& e) {
    YAML::Mark mark = when.Mark();
    const bool one_line = when.Scalar().find('\n') == std::string::npos;
    if (one_line) mark.column += int(e.position) + (when.Tag() == "!" ? 1 : 0);
    std::string message = e.what() + std::string(" in \"") + when.Scalar() + "\"";
    const std::string& text = when.Scalar();
    // A comma inside {...} ends a plain scalar: "max(velocity, outlet)" is cut there.
    if (when.Tag() != "!" &&
        std::count(text.begin(), text.end(), '(') > std::count(text.begin(), text.end(), ')'))
      message += " (in a {...} map, quote an expression that has commas)";
    checker.error(mark, path, message);
  }
}

// The map entry `key` of `node`, or an undefined node (yaml-cpp throws on the entries of one).
YAML::Node entry(const YAML::Node& node, const std::string& key) {
  if (!node || !node.IsMap() || !node[key]) return YAML::Node(YAML::NodeType::Undefined);
  return node[key];
}

// Every trigger's condition that the file gives, compiled with the constants and boxes: an
// output that follows the render trigger has its condition checked there.
void check_conditions(MapReader& top, const Config& c) {
  const YAML::Node when = entry(top.find("trigger"), "when");
  if (when && when.IsScalar() && !c.trigger.when.empty())
    check_condition(top.checker(), when, "trigger.when", c);
  const YAML::Node outputs = top.find("outputs");
  for (const ConfiguredOutput& o : c.outputs) {
    const YAML::Node own = entry(entry(entry(outputs, o.kind), "trigger"), "when");
    if (own && own.IsScalar() && !o.settings->trigger.when.empty())
      check_condition(top.checker(), own, "outputs." + o.kind + ".trigger.when", c);
  }
}

// ---- the top level

Key<Config> custom_key(std::string name, std::string type, std::string help,
                       std::string shown_default, std::function<void(MapReader&, Config&)> read,
                       std::function<void(YAML::Emitter&, const Config&)> emit) {
  Key<Config> k;
  k.name = std::move(name);
  k.type = std::move(type);
  k.help = std::move(help);
  k.shown_default = std::move(shown_default);
  k.read = std::move(read);
  k.emit = std::move(emit);
  return k;
}

std::vector<Key<Config>> top_keys(const ConfigKinds& kinds) {
  std::vector<Key<Config>> keys;
  keys.push_back(schema::text("output_folder", &Config::output_folder,
                              "base folder; outputs' relative folders are inside it"));
  keys.push_back(schema::text("log_level", &Config::log_level, "the library's log level")
                     .default_shown_as("(keep `VOXSPAN_LOG_LEVEL`)")
                     .only_when([](const Config& c) { return !c.log_level.empty(); }));
  keys.back().type = "`error` `warning` `info` `debug`";
  keys.push_back(
      schema::map("trigger", &Config::trigger, trigger_section(), "the render steps", true));
  keys.back().shown_default = "`{every_steps: 10, first: true, last: true}`";
  keys.push_back(custom_key("constants", "map of name: number",
                            "numbers the triggers' conditions name (`tank_length: 1.6`)", "`{}`",
                            read_constants, [](YAML::Emitter& e, const Config& c) {
                              e << YAML::BeginMap;
                              for (const auto& [name, value] : c.constants) {
                                e << YAML::Key << name << YAML::Value;
                                schema::emit_value(e, value);
                              }
                              e << YAML::EndMap;
                            }));
  keys.push_back(custom_key(
      "boxes", "map of name: [[x0, y0, z0], [x1, y1, z1]]",
      "boxes the conditions' reductions may be over (`max(velocity, outlet)`); the bounds are "
      "inclusive, `.inf` and `-.inf` allowed",
      "`{}`", read_boxes, [](YAML::Emitter& e, const Config& c) {
        e << YAML::BeginMap;
        for (const auto& [name, box] : c.boxes) {
          e << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginSeq;
          emit_corner(e, box.lo);
          emit_corner(e, box.hi);
          e << YAML::EndSeq;
        }
        e << YAML::EndMap;
      }));
  keys.push_back(custom_key(
      "views", "list of views",
      "the views rendered on each render step (`views[i]` of each kind below); `[]` renders "
      "nothing",
      "one view `main`", [&kinds](MapReader& r, Config& c) { read_views(r, c.views, kinds.views); },
      [&kinds](YAML::Emitter& e, const Config& c) {
        e << YAML::BeginSeq;
        for (const ConfiguredView& v : c.views)
          for (const ViewConfigKind& k : kinds.views)
            if (k.name == v.kind) k.emit(e, *v.settings);
        e << YAML::EndSeq;
      }));
  keys.push_back(
      schema::map("renderer", &Config::renderer, renderer_section(), "GL platform and GPU budget"));
  keys.push_back(schema::map("classification", &Config::classification, classification_section(),
                             "how cells are classified"));
  std::string output_names;
  for (const OutputConfigKind& k : kinds.outputs)
    output_names += (output_names.empty() ? "`" : ", `") + std::string(k.name) + "`";
  keys.push_back(custom_key(
      "outputs", "map", "the files written: " + output_names, "see `outputs.<kind>`",
      [&kinds](MapReader& r, Config& c) { read_outputs(r, c, kinds.outputs); },
      [&kinds](YAML::Emitter& e, const Config& c) {
        e << YAML::BeginMap;
        for (std::size_t i = 0; i < kinds.outputs.size(); ++i) {
          e << YAML::Key << std::string(kinds.outputs[i].name) << YAML::Value;
          kinds.outputs[i].emit(e, *c.outputs[i].settings);
        }
        e << YAML::EndMap;
      }));
  keys.push_back(schema::map("writer", &Config::writer, writer_section(), "the background writer"));
  keys.push_back(schema::map("live", &Config::live, live_section(), "the live page"));
  return keys;
}

// An enabled output's `views` names views of the config.
void check_named_views(MapReader& top, const Config& c) {
  if (!top.has("outputs")) return;
  std::string known;
  for (const ConfiguredView& v : c.views) known += (known.empty() ? "" : ", ") + v.settings->name;
  for (const ConfiguredOutput& o : c.outputs) {
    if (!o.settings->enabled) continue;
    for (const std::string& name : o.settings->named_views()) {
      const bool found = std::any_of(c.views.begin(), c.views.end(),
                                     [&](const auto& v) { return v.settings->name == name; });
      if (found) continue;
      const YAML::Node output = top.find("outputs")[o.kind];
      const std::string path = "outputs." + o.kind + ".views";
      top.checker().error(output && output["views"] ? output["views"] : output, path,
                          "there is no view \"" + name + "\" (the views: " + known + ")");
    }
  }
}

void check_top(MapReader& top, Config& c) {
  Checker& checker = top.checker();
  if (top.has("output_folder") && c.output_folder.empty())
    checker.error(top.find("output_folder"), "output_folder", "must not be empty");
  LogLevel level;
  if (top.has("log_level") && !parse_log_level(c.log_level, level))
    checker.error(top.find("log_level"), "log_level",
                  "expected one of error, warning, info, debug; got \"" + c.log_level + "\"");
  check_conditions(top, c);
  check_named_views(top, c);
}

Section<Config> top_section(const ConfigKinds& kinds) {
  return Section<Config>("", top_keys(kinds), check_top);
}

}  // namespace

std::filesystem::path Config::folder_of(const OutputSettings& output) const {
  std::filesystem::path folder(output.folder);
  return folder.is_absolute() ? folder : std::filesystem::path(output_folder) / folder;
}

std::size_t Config::output_index(std::string_view kind) const {
  for (std::size_t i = 0; i < outputs.size(); ++i)
    if (outputs[i].kind == kind) return i;
  throw make_error("the config has no output \"", kind, "\"");
}

OutputSettings& Config::output(std::string_view kind) {
  return *outputs[output_index(kind)].settings;
}

const OutputSettings& Config::output(std::string_view kind) const {
  return const_cast<Config&>(*this).output(kind);
}

std::vector<std::string> Config::output_attributes() const {
  std::vector<std::string> names;
  for (const ConfiguredOutput& o : outputs) {
    if (!o.settings->enabled) continue;
    for (const std::string& n : o.settings->needed_attributes())
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  }
  return names;
}

Config default_config(const ConfigKinds& kinds) {
  Config c;
  if (!kinds.views.empty()) {
    c.views.push_back({std::string(kinds.views.front().name), kinds.views.front().defaults()});
    c.views.back().settings->name = "main";
  }
  for (const OutputConfigKind& k : kinds.outputs)
    c.outputs.push_back({std::string(k.name), k.defaults()});
  for (ConfiguredOutput& o : c.outputs)
    if (o.settings->follows_render_trigger) o.settings->trigger = c.trigger;
  return c;
}

Config read_config(std::string_view yaml, std::string_view source_name, const ConfigKinds& kinds) {
  Checker checker{std::string(source_name)};
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml));
  } catch (const YAML::Exception& e) {
    checker.error(e.mark, "", "not valid YAML: " + e.msg);
    checker.throw_if_errors();
  }
  Config config = default_config(kinds);
  top_section(kinds).read(checker, root, "", config);
  checker.throw_if_errors();
  return config;
}

std::string write_config(const Config& config, const ConfigKinds& kinds) {
  YAML::Emitter e;
  top_section(kinds).emit(e, config);
  return std::string(e.c_str()) + "\n";
}

namespace {

void flatten(const YAML::Node& node, const std::string& path, std::vector<std::string>& lines) {
  if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string key = it->first.Scalar();
      flatten(it->second, path.empty() ? key : path + "." + key, lines);
    }
  } else if (node.IsSequence()) {
    if (node.size() == 0) lines.push_back(path + ": []");
    for (std::size_t i = 0; i < node.size(); ++i)
      flatten(node[i], path + "[" + std::to_string(i) + "]", lines);
  } else {
    lines.push_back(path + ": " + (node.IsScalar() ? node.Scalar() : std::string("~")));
  }
}

}  // namespace

bool is_local_address(std::string_view address) {
  if (address == "localhost") return true;
  in_addr v4{};
  return inet_pton(AF_INET, std::string(address).c_str(), &v4) == 1 &&
         (ntohl(v4.s_addr) >> 24) == 127;
}

std::vector<std::string> config_lines(const Config& config, const ConfigKinds& kinds) {
  std::vector<std::string> lines;
  flatten(YAML::Load(write_config(config, kinds)), "", lines);
  return lines;
}

std::string config_reference(const ConfigKinds& kinds) {
  const Config defaults = default_config(kinds);
  std::string s = "#### Top level\n\n" + top_section(kinds).reference(defaults);
  s += "\n#### `trigger` (every trigger)\n\n" + trigger_section().reference();
  for (const ViewConfigKind& k : kinds.views)
    s += "\n#### `views[i]` of kind `" + std::string(k.name) + "`\n\n" + k.reference();
  s += "\n#### `views[i].camera`\n\n" + camera_section().reference();
  s += "\n#### `renderer`\n\n" + renderer_section().reference();
  s += "\n#### `classification`\n\n" + classification_section().reference();
  for (const OutputConfigKind& k : kinds.outputs)
    s += "\n#### `outputs." + std::string(k.name) + "`\n\n" + k.reference();
  s += "\n#### `writer`\n\n" + writer_section().reference();
  s += "\n#### `live`\n\n" + live_section().reference();
  return s;
}

}  // namespace voxspan
