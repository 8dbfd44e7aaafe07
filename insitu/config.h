// insitu/config.h - what the runtime does, as typed settings loaded from YAML.
//
// The simulation describes its data once (the adapter's views); this file says what to do with
// it: which views (cameras) to render and how, when, and which files to write where. Loading
// checks everything against the schema (docs/runtime.md lists every key, type and default):
// unknown keys, wrong types and bad values are errors naming the key path, the file and the
// line, all reported at once, at start-up. Every key has a default, so an empty file works.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/trigger.h"

namespace voxspan {

using Vec3d = std::array<double, 3>;

enum class ShadingMode { opaque, translucent, refractive };
enum class GlPlatformChoice { automatic, nvidia, device, surfaceless };
enum class QueuePolicy { wait, drop };
// Automatic framing follows the fluid's bounds: grown over every render step so far (the
// camera only ever backs away: a steady video), refitted every step, or fixed at the first.
enum class Framing { grow, each_step, first };

const char* shading_mode_name(ShadingMode mode);
const char* gl_platform_name(GlPlatformChoice platform);
const char* queue_policy_name(QueuePolicy policy);
const char* framing_name(Framing framing);

struct CameraConfig {
  // Automatic framing: look along `direction` at the box of the particles (the boundary
  // particles' spheres, which enclose the fluid), from the distance at which the box, grown
  // by `margin` about its centre, just fits the view; `framing` says which box.
  // Manual: from `eye` at `target`.
  bool automatic = true;
  Vec3d eye{0, 0, 0};
  Vec3d target{0, 0, 0};
  Vec3d up{0, 0, 1};
  double fov_degrees = 40;  // vertical
  Vec3d direction{-1, 2, -0.8};
  double margin = 1.05;
  Framing framing = Framing::grow;
  bool operator==(const CameraConfig&) const = default;
};

struct ViewConfig {
  std::string name;  // default "view<i>"; names the PNG files and the stats section
  int width = 960;
  int height = 540;
  ShadingMode shading = ShadingMode::translucent;
  bool deep_ao = false;
  CameraConfig camera;
  double alpha_degrees = 14;  // normal-angle resolution of the depth layers (paper 001, 4.2)
  std::optional<double> gap;  // gap-bridging distance, world units; nullopt = auto (spacing)
  int max_spans = 0;          // stored spans per pixel; 0 = no cap (exact lists)
  std::optional<double> filter_radius;  // world units; nullopt = auto; 0 = off
  int max_layers = 16384;     // cap on depth layers, a multiple of 32 (paper: 16384)
  Vec3d absorption{0.45, 0.12, 0.05};  // Beer-Lambert, per world unit, RGB
  double ior = 1.33;                   // refractive index (refractive mode)
  int bounces = 3;                     // refraction/reflection bounces (refractive mode)
  bool operator==(const ViewConfig&) const = default;
};

struct RendererConfig {
  GlPlatformChoice platform = GlPlatformChoice::automatic;
  bool debug = false;
  double gpu_memory_mib = 512;  // budget for the tiled bit grid and span buffers
  bool operator==(const RendererConfig&) const = default;
};

struct ClassificationConfig {
  std::optional<std::int64_t> full_count;   // particles in a full cell; nullopt = from spacing
  std::optional<double> particle_spacing;   // world units; nullopt = as the solver reports it
  bool validate_grid = false;               // check each particle lies in the cell the grid says
  bool operator==(const ClassificationConfig&) const = default;
};

// Common to every output: on/off, its folder (relative to Config::output_folder unless
// absolute) and its trigger.
struct OutputCommon {
  bool enabled = false;
  std::string folder = ".";
  TriggerSpec trigger;
  bool operator==(const OutputCommon&) const = default;
};

// Defaults: PNG frames and stats on, at every render step (their trigger is the render
// trigger unless given); snapshots and VTK files off, every 100 steps when switched on.
struct PngOutputConfig : OutputCommon {
  PngOutputConfig() : OutputCommon{true, "frames", {10, 0, true, true}} {}
  bool operator==(const PngOutputConfig&) const = default;
};

struct StatsOutputConfig : OutputCommon {
  StatsOutputConfig() : OutputCommon{true, ".", {10, 0, true, true}} {}
  std::string file = "stats.jsonl";
  bool operator==(const StatsOutputConfig&) const = default;
};

struct VdbOutputConfig : OutputCommon {
  VdbOutputConfig() : OutputCommon{false, "snapshots", {100, 0, false, true}} {}
  // Sphere radius of every particle in the level set (world units); nullopt = half the
  // particle spacing, so that the level set holds the particles' own volume (each particle
  // stands for a cube of one spacing), or the render radius when the spacing is unknown.
  std::optional<double> radius;
  std::optional<double> voxel_size;  // world units; nullopt = the radius
  int half_width = 3;                // narrow band, voxels on each side
  std::optional<double> closing;     // gap closing distance; nullopt = the particle radius
  bool fill_inner = true;            // inner-full cells filled: the file holds the whole fluid
  bool cell_states = true;           // the cell-state grid
  std::vector<std::string> attributes;  // particle attributes as float/vec3 grids
  bool operator==(const VdbOutputConfig&) const = default;
};

struct VtkOutputConfig : OutputCommon {
  VtkOutputConfig() : OutputCommon{false, "vtk", {100, 0, false, true}} {}
  bool particles = true;  // .vtp of the boundary particles
  bool cells = true;      // .vti of the cell states
  std::vector<std::string> attributes;
  bool operator==(const VtkOutputConfig&) const = default;
};

struct OutputsConfig {
  PngOutputConfig png;
  StatsOutputConfig stats;
  VdbOutputConfig vdb;
  VtkOutputConfig vtk;
  bool operator==(const OutputsConfig&) const = default;
};

struct WriterConfig {
  int queue_size = 8;                  // jobs waiting for the writer thread
  QueuePolicy when_full = QueuePolicy::wait;
  bool fsync = true;                   // make files durable before they get their final name
  bool operator==(const WriterConfig&) const = default;
};

// One translucent view named "main" with automatic framing.
std::vector<ViewConfig> default_views();

struct Config {
  std::string output_folder = "voxspan-output";
  std::string log_level;  // empty: keep the logger's level (VOXSPAN_LOG_LEVEL)
  TriggerSpec trigger{10, 0, true, true};  // render steps
  std::vector<ViewConfig> views = default_views();
  RendererConfig renderer;
  ClassificationConfig classification;
  OutputsConfig outputs;
  WriterConfig writer;
  bool operator==(const Config&) const = default;

  // An output's folder: absolute as given, else under output_folder.
  std::filesystem::path folder_of(const OutputCommon& output) const;
};

// Throws voxspan::Error listing every problem ("<source>:<line>:<col>: <key path>: ...").
Config load_config_file(const std::filesystem::path& path);
Config load_config_string(std::string_view yaml, std::string_view source_name = "<config>");
// The effective configuration as YAML (every key, defaults included); loading it again
// gives the same Config.
std::string to_yaml(const Config& config);

}  // namespace voxspan
