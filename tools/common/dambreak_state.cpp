#include "tools/common/dambreak_state.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "tools/scenes/scenes.h"
#include "voxspan/error.h"
#ifdef VOXSPAN_HAVE_DAMBREAK
#include "sph.h"
#endif

namespace voxspan::tools {
namespace {

constexpr char kMagic[8] = {'V', 'X', 'D', 'B', 'S', 'T', '1', '\0'};

struct Header {
  char magic[8];
  std::uint64_t count;
  double spacing, time, requested_particles, column_width;
};

void classify(DamBreakState& s) {
  const auto view = ParticleView::soa(s.x.data(), s.y.data(), s.z.data(), s.x.size());
  ClassifyOptions options;
  options.particle_spacing = s.spacing;
  Classifier classifier;
  classifier.run(view, GridView(), options);
  s.classification = classifier.take_result();
}

// What both states do once their particles are in: a description (`format` takes the particle
// count and the time), a camera of 40 degrees with the state's up, the classification.
void finish(DamBreakState& s, const char* format, double time, glm::dvec3 eye, glm::dvec3 target) {
  char text[160];
  std::snprintf(text, sizeof text, format, s.x.size(), time);
  s.description = text;
  s.camera.eye = eye;
  s.camera.target = target;
  s.camera.up = s.up;
  s.camera.fov_y_degrees = 40;
  classify(s);
}

bool load(const std::string& path, double particles, double time, DamBreakState& s, double& a) {
  std::ifstream in(path, std::ios::binary);
  Header h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) return false;
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.time != time ||
      h.requested_particles != particles)
    return false;
  s.x.resize(h.count), s.y.resize(h.count), s.z.resize(h.count);
  for (auto* v : {&s.x, &s.y, &s.z})
    if (!in.read(reinterpret_cast<char*>(v->data()), std::streamsize(h.count * sizeof(float))))
      return false;
  s.spacing = h.spacing;
  a = h.column_width;
  return true;
}

void save(const std::string& path, double particles, double time, const DamBreakState& s,
          double a) {
  std::ofstream out(path, std::ios::binary);
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.count = s.x.size();
  h.spacing = s.spacing;
  h.time = time;
  h.requested_particles = particles;
  h.column_width = a;
  out.write(reinterpret_cast<const char*>(&h), sizeof h);
  for (const auto* v : {&s.x, &s.y, &s.z})
    out.write(reinterpret_cast<const char*>(v->data()), std::streamsize(v->size() * sizeof(float)));
  if (!out) throw make_error("cannot write the dam-break state to ", path);
}

}  // namespace

bool have_solver() {
#ifdef VOXSPAN_HAVE_DAMBREAK
  return true;
#else
  return false;
#endif
}

DamBreakState solver_dam_break(double particles, double time, const std::string& cache) {
  DamBreakState s;
  double a = 0;
  if (cache.empty() || !load(cache, particles, time, s, a)) {
#ifdef VOXSPAN_HAVE_DAMBREAK
    dambreak::Config config;
    config.particles = static_cast<std::size_t>(particles);
    dambreak::DamBreak sim(config);
    const auto t0 = std::chrono::steady_clock::now();
    while (sim.nondimensional_time() < time) {
      sim.step();
      if (sim.steps() % 500 == 0)
        std::printf("  solver: step %lld, T = %.2f, %.0f s\n", static_cast<long long>(sim.steps()),
                    sim.nondimensional_time(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const dambreak::Fluid& f = sim.fluid();
    s.x = f.x, s.y = f.y, s.z = f.z;
    s.spacing = sim.dx();
    a = config.column_width;
    if (!cache.empty()) save(cache, particles, time, s, a);
#else
    throw make_error("the dam-break solver is not built (VOXSPAN_BUILD_EXAMPLES=OFF) and ", cache,
                     " holds no state for ", particles, " particles at T = ", time);
#endif
  }
  s.length = a;  // up (z) and ground (0): DamBreakState's defaults, the solver's
  // Tank [0, 4a] x [0, a] x [0, 3a]: from the front, above, looking down the tank.
  finish(s, "WCSPH dam break (examples/dambreak), %zu fluid particles, T = %.2f", time,
         {2.3 * a, -4.7 * a, 3.5 * a}, {2.05 * a, 0.5 * a, 1.2 * a});
  return s;
}

DamBreakState ritter_dam_break(double particles, double t) {
  test::DamBreak shape;
  shape.spacing = test::dam_break_spacing(shape, particles);
  shape.radius = shape.spacing;
  shape.spray_fraction = 0.004;
  DamBreakState s;
  for (const ParticleSphere& p : test::dam_break(shape, t)) {
    s.x.push_back(p.x);
    s.y.push_back(p.y);
    s.z.push_back(p.z);
  }
  s.spacing = shape.spacing;
  s.up = {0, 1, 0};
  s.length = shape.width;
  finish(s, "Ritter-profile dam break (tools/scenes/scenes.h), %zu particles, t = %.2f s", t,
         {1.55, 0.75, 1.15}, {0.52, 0.12, 0.12});
  return s;
}

DamBreakState dam_break_state(const StateFlags& flags, const SceneArgs& scene) {
  const double t = scene.time;
  return flags.ritter ? ritter_dam_break(scene.particles, t < 0 ? 0.3 : t)
                      : solver_dam_break(scene.particles, t < 0 ? 5.0 : t, flags.state);
}

ShadeOptions bench_shading(const DamBreakState& s) {
  ShadeOptions o;
  o.environment.up = s.up;
  o.environment.rest_on_floor(s.ground, s.spacing);
  o.environment.ground_tile = s.length / 3;
  o.material.absorption = glm::dvec3(3.0, 1.0, 0.4) / s.length;
  o.ao.radius = 4 * s.spacing;
  return o;
}

}  // namespace voxspan::tools
