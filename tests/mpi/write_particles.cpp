// write_particles OUT.csv [PARTICLES] [T]: a dam break's particles (tools/scenes: the Ritter
// profile at time T, with spray) as CSV x,y,z,radius, for the MPI tests of the offline
// renderer: every rank reads the same file and renders its part.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tools/scenes/scenes.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_particles OUT.csv [PARTICLES] [T]\n");
    return 2;
  }
  voxspan::test::DamBreak shape;
  const double particles = argc > 2 ? std::atof(argv[2]) : 20000;
  const double t = argc > 3 ? std::atof(argv[3]) : 0.25;
  shape.spacing = voxspan::test::dam_break_spacing(shape, particles);
  shape.radius = shape.spacing;
  const voxspan::test::Particles p = voxspan::test::dam_break(shape, t);
  const std::filesystem::path out(argv[1]);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  FILE* f = std::fopen(argv[1], "w");
  if (f == nullptr) {
    std::perror(argv[1]);
    return 1;
  }
  std::fprintf(f, "x,y,z,radius\n");
  for (const voxspan::ParticleSphere& s : p)
    std::fprintf(f, "%.9g,%.9g,%.9g,%.9g\n", s.x, s.y, s.z, s.radius);
  std::fclose(f);
  std::printf("%zu particles, spacing %.6g, in %s\n", p.size(), shape.spacing, argv[1]);
  return 0;
}
