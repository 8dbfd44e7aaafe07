#include "render/gl/passes/volume_march.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/cpu/volume_adaptive.h"
#include "render/gl/info.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {
enum Binding : GLuint {
  kSupports,
  kTileStart,
  kTileLists,
  kDepths,
  kTransfer,
  kPicture,
  kDepth,
  kCounts,
  kBundleCells,
  kCells,
  kSuperPixels,
  kWalls,
};
constexpr std::size_t kCountWords = 8;
// llvmpipe's 65535 loop passes per invocation, less what a thread may spend between two checks
// of the budget (a chunk of 64 supports over a slab, 64 * 41, then a slab's compositing with 4
// iso surfaces and its plans' cells, 32 * 36 + 41).
constexpr unsigned kSoftwareLoopBudget = 65535 - 64 * 41 - (32 * 36 + 41) - 512;
// The iso arrays' elements by name (GL sets an array uniform element by element).
constexpr const char* kIsoValue[] = {"u_iso_value[0]", "u_iso_value[1]", "u_iso_value[2]",
                                     "u_iso_value[3]"};
constexpr const char* kIsoOpacity[] = {"u_iso_opacity[0]", "u_iso_opacity[1]", "u_iso_opacity[2]",
                                       "u_iso_opacity[3]"};
constexpr const char* kIsoColor[] = {"u_iso_color[0]", "u_iso_color[1]", "u_iso_color[2]",
                                     "u_iso_color[3]"};
static_assert(VX_MAX_ISO == 4);
constexpr const char* kRunLength[] = {"u_run_length[0]", "u_run_length[1]", "u_run_length[2]",
                                      "u_run_length[3]", "u_run_length[4]"};
static_assert(kCellShift == 4, "the shader's runs of a cell are bits of a 16-bit word");

// Uploads `values` into `buffer`, grown as needed (a buffer is never empty: GL binds none).
template <class T> void upload(gl::Buffer& buffer, const std::vector<T>& values);

// Per pixel the backdrop's colour and, in alpha, the first of the setup's samples behind its
// walls (as the CPU caster finds it, VolumeLattice::last_at_or_before), -1 where none stands.
std::vector<glm::vec4> wall_ends(const Backdrop& backdrop, const VolumeSetup& setup) {
  std::vector<glm::vec4> out(backdrop.pixels.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    const glm::vec4 b = backdrop.pixels[k];
    const std::int64_t end =
        b.a == Backdrop::kNoWall
            ? -1
            : std::clamp<std::int64_t>(
                  setup.lattice.last_at_or_before(double(b.a)) + 1 - setup.base, 0,
                  std::int64_t(setup.depths.size()));
    out[k] = glm::vec4(glm::vec3(b), float(end));
  }
  return out;
}

template <class T> void upload(gl::Buffer& buffer, const std::vector<T>& values) {
  buffer.reserve(std::max<std::size_t>(values.size() * sizeof(T), 16));
  if (!values.empty()) buffer.upload(values.data(), values.size() * sizeof(T));
}
}  // namespace

VolumeMarchPass::VolumeMarchPass(const gl::ShaderLibrary& shaders)
    : software_(gl::software_renderer()),
      program_(shaders.compute("render/gl/passes/volume_march.comp",
                               gl::defines({{"VM_SUPPORTS", kSupports},
                                            {"VM_TILE_START", kTileStart},
                                            {"VM_TILE_LISTS", kTileLists},
                                            {"VM_DEPTHS", kDepths},
                                            {"VM_TRANSFER", kTransfer},
                                            {"VM_PICTURE", kPicture},
                                            {"VM_DEPTH", kDepth},
                                            {"VM_COUNTS", kCounts},
                                            {"VM_BUNDLE_CELLS", kBundleCells},
                                            {"VM_CELLS", kCells},
                                            {"VM_SUPER_PIXELS", kSuperPixels},
                                            {"VM_FULL_RATE", GpuPlans::kFullRate},
                                            {"VM_LEVEL_BITS", GpuPlans::kLevelBits},
                                            {"VM_WALLS", kWalls},
                                            {"VM_CELL_SHIFT", kCellShift},
                                            {"VM_SUPER_PIXEL", kSuperPixel},
                                            {"VM_SLAB", kSlab},
                                            {"VX_TRANSFER_ENTRIES", VX_TRANSFER_ENTRIES},
                                            {"VX_MAX_ISO", VX_MAX_ISO}}))) {}

bool VolumeMarchPass::run(const Camera& camera, const VolumeSetup& setup,
                          const VolumeOptions& options, const model::VolumeHost& host,
                          VolumeFrame& out, VolumeCounts& counts) {
  const std::size_t pixels = std::size_t(camera.width) * std::size_t(camera.height);
  upload(supports_, setup.supports);
  upload(tile_start_, setup.tile_start);
  upload(tile_lists_, setup.tile_lists);
  upload(depths_, setup.depths);
  std::vector<glm::vec4> table(VX_TRANSFER_ENTRIES);
  for (int k = 0; k < VX_TRANSFER_ENTRIES; ++k) table[std::size_t(k)] = host.vx_transfer_entry(k);
  upload(transfer_, table);
  upload(bundle_cells_, setup.plans.bundle_cells);
  upload(cells_, setup.plans.cells);
  upload(super_pixels_, setup.plans.super_pixels);
  upload(walls_, options.backdrop != nullptr ? wall_ends(*options.backdrop, setup)
                                             : std::vector<glm::vec4>{});
  picture_.reserve(pixels * sizeof(glm::vec4));
  depth_.reserve(std::max<std::size_t>(pixels * sizeof(float), 16));
  counts_.reserve(kCountWords * sizeof(std::uint32_t));
  counts_.clear();
  gl::bind_storage({{supports_, kSupports},
                    {tile_start_, kTileStart},
                    {tile_lists_, kTileLists},
                    {depths_, kDepths},
                    {transfer_, kTransfer},
                    {picture_, kPicture},
                    {depth_, kDepth},
                    {counts_, kCounts},
                    {bundle_cells_, kBundleCells},
                    {cells_, kCells},
                    {super_pixels_, kSuperPixels},
                    {walls_, kWalls}});

  const gl::Program& p = program_;
  set_shade_uniforms(p, host);
  const ViewFrame f(camera);
  const int bundles_x = (camera.width + 7) / 8, bundles_y = (camera.height + 7) / 8;
  p.set("u_image", glm::ivec2(camera.width, camera.height));
  p.set("u_tiles_x", setup.tiles_x);
  p.set("u_samples", int(setup.depths.size()));
  p.set("u_tan_half", glm::dvec2(f.tan_half_x, f.tan_half_y));
  p.set("u_eye", glm::vec3(f.eye));
  p.set("u_right", glm::vec3(f.right));
  p.set("u_up", glm::vec3(f.up));
  p.set("u_forward", glm::vec3(f.forward));
  p.set("u_near", setup.near);
  p.set("u_kernel", unsigned(options.kernel));
  p.set("u_shepard", options.shepard ? 1 : 0);
  p.set("u_weight_floor", float(options.weight_floor));
  p.set("u_termination", float(options.termination));
  p.set("u_half_extent", setup.lattice.half_extent);
  p.set("u_lattice_k", setup.lattice.k);
  p.set("u_background", options.background ? 1 : 0);
  p.set("u_walls", options.backdrop != nullptr ? 1 : 0);
  p.set("u_adaptive", setup.adaptive ? 1 : 0);
  p.set("u_phase", int(setup.base & (kCellSamples - 1)));
  // The depths of a run of 2^l samples over its first's, as the CPU march sums them.
  for (int l = 0; l <= kCellShift; ++l) {
    double length = 0;
    for (int j = 0; j < 1 << l; ++j) length += std::exp(double(j) * setup.lattice.log_step);
    p.set(kRunLength[l], length);
  }
  p.set("u_budget", software_ ? kSoftwareLoopBudget : 0u);
  p.set("u_tf_log", host.u_tf_log);
  p.set("u_tf_lo", host.u_tf_lo);
  p.set("u_tf_scale", host.u_tf_scale);
  p.set("u_opacity_length", host.u_opacity_length);
  p.set("u_mode", host.u_mode);
  p.set("u_iso_count", host.u_iso_count);
  for (int k = 0; k < VX_MAX_ISO; ++k) {
    p.set(kIsoValue[k], host.u_iso_value[k]);
    p.set(kIsoOpacity[k], host.u_iso_opacity[k]);
    p.set(kIsoColor[k], host.u_iso_color[k]);
  }
  p.set("u_ambient", host.u_ambient);
  p.set("u_light", host.u_light);
  p.dispatch(GLuint(bundles_x), GLuint(bundles_y));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);

  out.reset(camera.width, camera.height);
  picture_.download(out.picture.rgba.data(), pixels * sizeof(glm::vec4));
  depth_.download(out.depth.data(), pixels * sizeof(float));
  const auto c = counts_.read_array<std::uint32_t, kCountWords>();
  counts.samples += c[0];
  counts.kernel_evaluations += std::int64_t(c[1]) + (std::int64_t(c[2]) << 32);
  counts.rays_stopped += c[3];
  counts.iso_hits += c[4];
  counts.iso_hits_unlit += c[5];
  counts.samples_skipped += c[7];
  return c[6] == 0;
}

}  // namespace voxspan
