// write_particles OUT.csv [PARTICLES] [T] [--solver]: a dam break's particles as CSV
// x,y,z,radius,height (height = z: a field for the slices to interpolate), for the MPI tests of the
// offline renderer (every rank reads the same file and renders its part): the Ritter profile of
// tools/scenes at time T seconds, with spray, or with
// --solver the WCSPH solver's (examples/dambreak) at Martin & Moyce's T.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "sph.h"
#include "tools/scenes/scenes.h"

namespace {

voxspan::test::Particles ritter(double particles, double t) {
  voxspan::test::DamBreak shape;
  shape.spacing = voxspan::test::dam_break_spacing(shape, particles);
  shape.radius = shape.spacing;
  return voxspan::test::dam_break(shape, t);
}

voxspan::test::Particles solved(double particles, double nondimensional_time) {
  dambreak::Config config;
  config.particles = std::size_t(particles);
  dambreak::DamBreak sim(config);
  while (sim.nondimensional_time() < nondimensional_time) sim.step();
  const dambreak::Fluid& f = sim.fluid();
  voxspan::test::Particles p;
  for (std::size_t i = 0; i < f.size(); ++i) p.push_back({f.x[i], f.y[i], f.z[i], float(sim.dx())});
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_particles OUT.csv [PARTICLES] [T]\n");
    return 2;
  }
  const double particles = argc > 2 ? std::atof(argv[2]) : 20000;
  const double t = argc > 3 ? std::atof(argv[3]) : 0.25;
  const bool solver = argc > 4 && std::string(argv[4]) == "--solver";
  const voxspan::test::Particles p = solver ? solved(particles, t) : ritter(particles, t);
  const std::filesystem::path out(argv[1]);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  FILE* f = std::fopen(argv[1], "w");
  if (f == nullptr) {
    std::perror(argv[1]);
    return 1;
  }
  std::fprintf(f, "x,y,z,radius,height\n");
  for (const voxspan::ParticleSphere& s : p)
    std::fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g\n", s.x, s.y, s.z, s.radius, s.z);
  std::fclose(f);
  std::printf("%zu particles in %s\n", p.size(), argv[1]);
  return 0;
}
