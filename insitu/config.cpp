// The config schema: every key, its type, range and default (docs/runtime.md says the same in
// prose). The mechanism (typed getters, unknown keys, lines) is in yaml_reader.
#include "insitu/config.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "insitu/yaml_reader.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

using yaml::Checker;
using yaml::MapReader;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Names that become parts of file names: letters, digits, '_', '-', '.'.
bool is_file_name_part(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return true;
}

double length(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// sin of the angle between a and b is |a x b| / (|a| |b|).
bool parallel(const Vec3d& a, const Vec3d& b) {
  Vec3d c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return length(c) <= 1e-6 * length(a) * length(b);
}

void read_trigger(MapReader& parent, std::string_view key, TriggerSpec& out) {
  MapReader r(parent.checker(), parent.find(key), parent.path(key),
              {"every_steps", "every_time", "first", "last"});
  if (!parent.has(key)) return;
  // A trigger given replaces the default as a whole: unset conditions are off.
  TriggerSpec t{0, 0, false, false};
  r.get_int("every_steps", t.every_steps, 0, std::numeric_limits<std::int64_t>::max());
  r.get_double("every_time", t.every_time, 0, kInf);
  r.get("first", t.first);
  r.get("last", t.last);
  out = t;
}

void read_camera(MapReader& view, CameraConfig& c) {
  if (!view.has("camera")) return;
  MapReader r(view.checker(), view.find("camera"), view.path("camera"),
              {"auto", "eye", "target", "up", "fov", "direction", "margin", "framing"});
  bool has_eye = r.get_vec3("eye", c.eye);
  bool has_target = r.get_vec3("target", c.target);
  c.automatic = !(r.has("eye") || r.has("target"));
  r.get("auto", c.automatic);
  r.get_vec3("up", c.up);
  r.get_double("fov", c.fov_degrees, 0, 179, true);
  r.get_vec3("direction", c.direction);
  r.get_double("margin", c.margin, 0, 100, true);
  r.get_enum("framing", c.framing,
             {{"grow", Framing::grow}, {"each_step", Framing::each_step}, {"first", Framing::first}});

  Checker& ch = r.checker();
  if (length(c.up) == 0) ch.error(r.find("up"), r.path("up"), "must not be zero");
  if (c.automatic) {
    if (r.has("eye") || r.has("target"))
      ch.error(r.find(r.has("eye") ? "eye" : "target"), r.path(r.has("eye") ? "eye" : "target"),
               "automatic framing (auto: true) chooses the eye and target itself; remove it or "
               "set auto: false");
    if (length(c.direction) == 0)
      ch.error(r.find("direction"), r.path("direction"), "must not be zero");
    else if (length(c.up) > 0 && parallel(c.direction, c.up))
      ch.error(r.find("direction"), r.path("direction"), "must not be parallel to camera.up");
  } else {
    for (const char* key : {"direction", "margin", "framing"})
      if (r.has(key))
        ch.error(r.find(key), r.path(key),
                 "is for automatic framing; a camera with eye and target looks at the target");
    if (!r.has("eye") || !r.has("target")) {
      ch.error(r.node(), view.path("camera"), "a manual camera needs both eye and target");
    } else if (has_eye && has_target) {
      Vec3d d{c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]};
      if (length(d) == 0)
        ch.error(r.find("target"), r.path("target"), "must differ from camera.eye");
      else if (length(c.up) > 0 && parallel(d, c.up))
        ch.error(r.find("up"), r.path("up"), "must not be parallel to the viewing direction");
    }
  }
}

ViewConfig read_view(Checker& checker, const YAML::Node& node, const std::string& path,
                     std::size_t index) {
  ViewConfig v;
  v.name = "view" + std::to_string(index);
  MapReader r(checker, node, path,
              {"name", "width", "height", "shading", "deep_ao", "camera", "alpha", "gap",
               "max_spans", "filter_radius", "max_layers", "absorption", "ior", "bounces"});
  if (r.get("name", v.name) && !is_file_name_part(v.name))
    checker.error(r.find("name"), r.path("name"),
                  "must be letters, digits, '_', '-' or '.' (it names files); got \"" + v.name +
                      "\"");
  r.get_int("width", v.width, 1, 16384);
  r.get_int("height", v.height, 1, 16384);
  r.get_enum("shading", v.shading,
             {{"opaque", ShadingMode::opaque},
              {"translucent", ShadingMode::translucent},
              {"refractive", ShadingMode::refractive}});
  r.get("deep_ao", v.deep_ao);
  read_camera(r, v.camera);
  r.get_double("alpha", v.alpha_degrees, 0, 45, true);
  r.get_auto_double("gap", v.gap, 0, kInf);
  r.get_int("max_spans", v.max_spans, 0, 1 << 20);
  r.get_auto_double("filter_radius", v.filter_radius, 0, kInf);
  if (r.get_int("max_layers", v.max_layers, 32, 1 << 20) && v.max_layers % 32 != 0)
    checker.error(r.find("max_layers"), r.path("max_layers"),
                  "must be a multiple of 32 (a column's layers are stored in 32-bit words); "
                  "got " + std::to_string(v.max_layers));
  if (r.get_vec3("absorption", v.absorption) &&
      (v.absorption[0] < 0 || v.absorption[1] < 0 || v.absorption[2] < 0))
    checker.error(r.find("absorption"), r.path("absorption"), "must not be negative");
  r.get_double("ior", v.ior, 1, 4);
  r.get_int("bounces", v.bounces, 0, 16);
  return v;
}

void read_views(MapReader& top, std::vector<ViewConfig>& views) {
  if (!top.has("views")) return;
  YAML::Node node = top.find("views");
  Checker& checker = top.checker();
  views.clear();
  if (node.IsNull()) return;
  if (!node.IsSequence()) {
    checker.error(node, "views", "expected a list of views (\"- name: ...\"); got " +
                                     yaml::describe(node));
    return;
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < node.size(); ++i) {
    std::string path = "views[" + std::to_string(i) + "]";
    views.push_back(read_view(checker, node[i], path, i));
    if (!names.insert(views.back().name).second)
      checker.error(node[i], path + ".name", "\"" + views.back().name + "\" names two views");
  }
}

void read_output_common(MapReader& r, OutputCommon& out, const TriggerSpec& render_trigger,
                        bool inherits_render_trigger) {
  r.get("enabled", out.enabled);
  if (r.get("folder", out.folder) && out.folder.empty())
    r.checker().error(r.find("folder"), r.path("folder"), "must not be empty");
  if (inherits_render_trigger) out.trigger = render_trigger;
  read_trigger(r, "trigger", out.trigger);
  if (out.enabled && out.trigger.never_fires())
    r.checker().error(r.has("trigger") ? r.find("trigger") : r.node(), r.path("trigger"),
                      "never fires while the output is enabled: set every_steps, every_time, "
                      "first or last, or enabled: false");
}

void read_attribute_names(MapReader& r, std::vector<std::string>& names) {
  if (!r.get_strings("attributes", names)) return;
  std::set<std::string> seen;
  for (const std::string& n : names)
    if (!seen.insert(n).second)
      r.checker().error(r.find("attributes"), r.path("attributes"), "\"" + n + "\" given twice");
}

void read_outputs(MapReader& top, Config& c) {
  MapReader outs(top.checker(), top.find("outputs"), "outputs", {"png", "stats", "vdb", "vtk"});
  {
    MapReader r(top.checker(), outs.find("png"), "outputs.png", {"enabled", "folder", "trigger"});
    read_output_common(r, c.outputs.png, c.trigger, true);
  }
  {
    MapReader r(top.checker(), outs.find("stats"), "outputs.stats",
                {"enabled", "folder", "trigger", "file"});
    read_output_common(r, c.outputs.stats, c.trigger, true);
    if (r.get("file", c.outputs.stats.file) && !is_file_name_part(c.outputs.stats.file))
      r.checker().error(r.find("file"), r.path("file"),
                        "must be a plain file name (the folder is outputs.stats.folder)");
  }
  {
    VdbOutputConfig& v = c.outputs.vdb;
    MapReader r(top.checker(), outs.find("vdb"), "outputs.vdb",
                {"enabled", "folder", "trigger", "radius", "voxel_size", "half_width", "closing",
                 "fill_inner", "cell_states", "attributes"});
    read_output_common(r, v, c.trigger, false);
    r.get_auto_double("radius", v.radius, 0, kInf, true);
    r.get_auto_double("voxel_size", v.voxel_size, 0, kInf, true);
    r.get_int("half_width", v.half_width, 1, 64);
    r.get_auto_double("closing", v.closing, 0, kInf);
    r.get("fill_inner", v.fill_inner);
    r.get("cell_states", v.cell_states);
    read_attribute_names(r, v.attributes);
  }
  {
    VtkOutputConfig& v = c.outputs.vtk;
    MapReader r(top.checker(), outs.find("vtk"), "outputs.vtk",
                {"enabled", "folder", "trigger", "particles", "cells", "attributes"});
    read_output_common(r, v, c.trigger, false);
    r.get("particles", v.particles);
    r.get("cells", v.cells);
    read_attribute_names(r, v.attributes);
    if (v.enabled && !v.particles && !v.cells)
      r.checker().error(r.node(), "outputs.vtk",
                        "enabled but writes nothing: set particles or cells to true");
  }
}

Config read_config(const YAML::Node& root, Checker& checker) {
  Config c;
  MapReader top(checker, root, "",
                {"output_folder", "log_level", "trigger", "views", "renderer", "classification",
                 "outputs", "writer"});
  if (top.get("output_folder", c.output_folder) && c.output_folder.empty())
    checker.error(top.find("output_folder"), "output_folder", "must not be empty");
  if (top.get("log_level", c.log_level)) {
    LogLevel level;
    if (!parse_log_level(c.log_level, level))
      checker.error(top.find("log_level"), "log_level",
                    "expected one of error, warning, info, debug; got \"" + c.log_level + "\"");
  }
  read_trigger(top, "trigger", c.trigger);
  read_views(top, c.views);
  {
    MapReader r(checker, top.find("renderer"), "renderer",
                {"gl_platform", "debug", "gpu_memory_mib"});
    r.get_enum("gl_platform", c.renderer.platform,
               {{"auto", GlPlatformChoice::automatic},
                {"nvidia", GlPlatformChoice::nvidia},
                {"device", GlPlatformChoice::device},
                {"surfaceless", GlPlatformChoice::surfaceless}});
    r.get("debug", c.renderer.debug);
    r.get_double("gpu_memory_mib", c.renderer.gpu_memory_mib, 1, 1 << 24);
  }
  {
    MapReader r(checker, top.find("classification"), "classification",
                {"full_count", "particle_spacing", "validate_grid"});
    r.get_auto_int("full_count", c.classification.full_count, 1, 1 << 20);
    r.get_auto_double("particle_spacing", c.classification.particle_spacing, 0, kInf, true);
    r.get("validate_grid", c.classification.validate_grid);
  }
  read_outputs(top, c);
  {
    MapReader r(checker, top.find("writer"), "writer", {"queue_size", "when_full", "fsync"});
    r.get_int("queue_size", c.writer.queue_size, 1, 4096);
    r.get_enum("when_full", c.writer.when_full,
               {{"wait", QueuePolicy::wait}, {"drop", QueuePolicy::drop}});
    r.get("fsync", c.writer.fsync);
  }
  return c;
}

// ---- to_yaml ----

void emit_vec3(YAML::Emitter& e, const char* key, const Vec3d& v) {
  e << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2]
    << YAML::EndSeq;
}
template <class T>
void emit_auto(YAML::Emitter& e, const char* key, const std::optional<T>& v) {
  e << YAML::Key << key << YAML::Value;
  if (v)
    e << *v;
  else
    e << "auto";
}
void emit_trigger(YAML::Emitter& e, const TriggerSpec& t) {
  e << YAML::Key << "trigger" << YAML::Value << YAML::Flow << YAML::BeginMap
    << YAML::Key << "every_steps" << YAML::Value << t.every_steps
    << YAML::Key << "every_time" << YAML::Value << t.every_time
    << YAML::Key << "first" << YAML::Value << t.first
    << YAML::Key << "last" << YAML::Value << t.last << YAML::EndMap;
}
void emit_common(YAML::Emitter& e, const OutputCommon& o) {
  e << YAML::Key << "enabled" << YAML::Value << o.enabled;
  e << YAML::Key << "folder" << YAML::Value << o.folder;
  emit_trigger(e, o.trigger);
}
void emit_names(YAML::Emitter& e, const std::vector<std::string>& names) {
  e << YAML::Key << "attributes" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const auto& n : names) e << n;
  e << YAML::EndSeq;
}

void emit_view(YAML::Emitter& e, const ViewConfig& v) {
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << v.name;
  e << YAML::Key << "width" << YAML::Value << v.width;
  e << YAML::Key << "height" << YAML::Value << v.height;
  e << YAML::Key << "shading" << YAML::Value << shading_mode_name(v.shading);
  e << YAML::Key << "deep_ao" << YAML::Value << v.deep_ao;
  e << YAML::Key << "camera" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "auto" << YAML::Value << v.camera.automatic;
  if (!v.camera.automatic) {
    emit_vec3(e, "eye", v.camera.eye);
    emit_vec3(e, "target", v.camera.target);
  }
  emit_vec3(e, "up", v.camera.up);
  e << YAML::Key << "fov" << YAML::Value << v.camera.fov_degrees;
  if (v.camera.automatic) emit_vec3(e, "direction", v.camera.direction);
  if (v.camera.automatic) {
    e << YAML::Key << "margin" << YAML::Value << v.camera.margin;
    e << YAML::Key << "framing" << YAML::Value << framing_name(v.camera.framing);
  }
  e << YAML::EndMap;
  e << YAML::Key << "alpha" << YAML::Value << v.alpha_degrees;
  emit_auto(e, "gap", v.gap);
  e << YAML::Key << "max_spans" << YAML::Value << v.max_spans;
  emit_auto(e, "filter_radius", v.filter_radius);
  e << YAML::Key << "max_layers" << YAML::Value << v.max_layers;
  emit_vec3(e, "absorption", v.absorption);
  e << YAML::Key << "ior" << YAML::Value << v.ior;
  e << YAML::Key << "bounces" << YAML::Value << v.bounces;
  e << YAML::EndMap;
}

}  // namespace

const char* shading_mode_name(ShadingMode mode) {
  switch (mode) {
    case ShadingMode::opaque: return "opaque";
    case ShadingMode::translucent: return "translucent";
    case ShadingMode::refractive: return "refractive";
  }
  return "?";
}

const char* gl_platform_name(GlPlatformChoice platform) {
  switch (platform) {
    case GlPlatformChoice::automatic: return "auto";
    case GlPlatformChoice::nvidia: return "nvidia";
    case GlPlatformChoice::device: return "device";
    case GlPlatformChoice::surfaceless: return "surfaceless";
  }
  return "?";
}

const char* queue_policy_name(QueuePolicy policy) {
  return policy == QueuePolicy::wait ? "wait" : "drop";
}

const char* framing_name(Framing framing) {
  switch (framing) {
    case Framing::grow: return "grow";
    case Framing::each_step: return "each_step";
    case Framing::first: return "first";
  }
  return "?";
}

std::vector<ViewConfig> default_views() {
  ViewConfig main;
  main.name = "main";
  return {main};
}

std::filesystem::path Config::folder_of(const OutputCommon& output) const {
  std::filesystem::path folder(output.folder);
  return folder.is_absolute() ? folder : std::filesystem::path(output_folder) / folder;
}

Config load_config_string(std::string_view yaml, std::string_view source_name) {
  Checker checker{std::string(source_name)};
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml));
  } catch (const YAML::Exception& e) {
    checker.error(e.mark, "", "not valid YAML: " + e.msg);
    checker.throw_if_errors();
  }
  Config config = read_config(root, checker);
  checker.throw_if_errors();
  return config;
}

Config load_config_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error("cannot read config file ", path.string(), ": ", std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw make_error("cannot read config file ", path.string());
  return load_config_string(text.str(), path.string());
}

std::string to_yaml(const Config& c) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << YAML::BeginMap;
  e << YAML::Key << "output_folder" << YAML::Value << c.output_folder;
  if (!c.log_level.empty()) e << YAML::Key << "log_level" << YAML::Value << c.log_level;
  emit_trigger(e, c.trigger);
  e << YAML::Key << "views" << YAML::Value << YAML::BeginSeq;
  for (const ViewConfig& v : c.views) emit_view(e, v);
  e << YAML::EndSeq;
  e << YAML::Key << "renderer" << YAML::Value << YAML::BeginMap
    << YAML::Key << "gl_platform" << YAML::Value << gl_platform_name(c.renderer.platform)
    << YAML::Key << "debug" << YAML::Value << c.renderer.debug
    << YAML::Key << "gpu_memory_mib" << YAML::Value << c.renderer.gpu_memory_mib << YAML::EndMap;
  e << YAML::Key << "classification" << YAML::Value << YAML::BeginMap;
  emit_auto(e, "full_count", c.classification.full_count);
  emit_auto(e, "particle_spacing", c.classification.particle_spacing);
  e << YAML::Key << "validate_grid" << YAML::Value << c.classification.validate_grid
    << YAML::EndMap;
  e << YAML::Key << "outputs" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "png" << YAML::Value << YAML::BeginMap;
  emit_common(e, c.outputs.png);
  e << YAML::EndMap;
  e << YAML::Key << "stats" << YAML::Value << YAML::BeginMap;
  emit_common(e, c.outputs.stats);
  e << YAML::Key << "file" << YAML::Value << c.outputs.stats.file << YAML::EndMap;
  const VdbOutputConfig& vdb = c.outputs.vdb;
  e << YAML::Key << "vdb" << YAML::Value << YAML::BeginMap;
  emit_common(e, vdb);
  emit_auto(e, "radius", vdb.radius);
  emit_auto(e, "voxel_size", vdb.voxel_size);
  e << YAML::Key << "half_width" << YAML::Value << vdb.half_width;
  emit_auto(e, "closing", vdb.closing);
  e << YAML::Key << "fill_inner" << YAML::Value << vdb.fill_inner;
  e << YAML::Key << "cell_states" << YAML::Value << vdb.cell_states;
  emit_names(e, vdb.attributes);
  e << YAML::EndMap;
  const VtkOutputConfig& vtk = c.outputs.vtk;
  e << YAML::Key << "vtk" << YAML::Value << YAML::BeginMap;
  emit_common(e, vtk);
  e << YAML::Key << "particles" << YAML::Value << vtk.particles;
  e << YAML::Key << "cells" << YAML::Value << vtk.cells;
  emit_names(e, vtk.attributes);
  e << YAML::EndMap;
  e << YAML::EndMap;
  e << YAML::Key << "writer" << YAML::Value << YAML::BeginMap
    << YAML::Key << "queue_size" << YAML::Value << c.writer.queue_size
    << YAML::Key << "when_full" << YAML::Value << queue_policy_name(c.writer.when_full)
    << YAML::Key << "fsync" << YAML::Value << c.writer.fsync << YAML::EndMap;
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

}  // namespace voxspan
