// write_particles OUT.csv|OUT.hdf5 [PARTICLES] [T] [--solver]: a dam break's particles as CSV
// x,y,z,radius,height (height = z: a field for the slices to interpolate), for the MPI tests of the
// offline renderer (every rank reads the same file and renders its part): the Ritter profile of
// tools/scenes at time T seconds, with spray, or with
// --solver the WCSPH solver's (examples/dambreak) at Martin & Moyce's T. OUT.hdf5: in PySPH's
// layout, the fluid (moving, with height, m and rho) and the tank's floor and back wall as a
// `wall` array that stands still, which the tool draws as scenery.
#include <hdf5.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

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

// One PySPH particle array: its properties, one value per particle.
void write_array(hid_t particles, const char* name,
                 const std::vector<std::pair<const char*, std::vector<double>>>& properties) {
  const hid_t group = H5Gcreate2(particles, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t arrays = H5Gcreate2(group, "arrays", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (const auto& [prop, values] : properties) {
    const hsize_t n = values.size();
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t set =
        H5Dcreate2(arrays, prop, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(set);
    H5Sclose(space);
  }
  H5Gclose(arrays);
  H5Gclose(group);
}

// The particles as PySPH's output, with the tank's floor and back wall under and behind them.
bool write_pysph(const char* path, const voxspan::test::Particles& p) {
  const hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) return false;
  const hid_t particles = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const double dx = p.empty() ? 0.01 : p.front().radius;
  std::vector<double> x, y, z, u, m, rho;
  for (const voxspan::ParticleSphere& s : p) {
    x.push_back(s.x), y.push_back(s.y), z.push_back(s.z);
    u.push_back(1), m.push_back(1000 * dx * dx * dx), rho.push_back(1000);
  }
  write_array(particles, "fluid",
              {{"x", x}, {"y", y}, {"z", z}, {"u", u}, {"height", z}, {"m", m}, {"rho", rho}});
  const voxspan::test::DamBreak tank;
  std::vector<double> wx, wy, wz, still;
  for (double a = -dx; a <= tank.tank_length + dx; a += dx) {
    for (double b = 0; b <= tank.depth; b += dx)  // the floor
      wx.push_back(a), wy.push_back(b), wz.push_back(-dx);
    for (double c = 0; c <= 0.5 * tank.height; c += dx)  // the back wall
      wx.push_back(a), wy.push_back(tank.depth + dx), wz.push_back(c);
  }
  still.assign(wx.size(), 0.0);
  write_array(particles, "wall", {{"x", wx}, {"y", wy}, {"z", wz}, {"u", still}});
  H5Gclose(particles);
  return H5Fclose(f) >= 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_particles OUT.csv|OUT.hdf5 [PARTICLES] [T] [--solver]\n");
    return 2;
  }
  const double particles = argc > 2 ? std::atof(argv[2]) : 20000;
  const double t = argc > 3 ? std::atof(argv[3]) : 0.25;
  const bool solver = argc > 4 && std::string(argv[4]) == "--solver";
  const voxspan::test::Particles p = solver ? solved(particles, t) : ritter(particles, t);
  const std::filesystem::path out(argv[1]);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  if (out.extension() == ".hdf5") {
    if (!write_pysph(argv[1], p)) {
      std::fprintf(stderr, "write_particles: cannot write %s\n", argv[1]);
      return 1;
    }
    std::printf("%zu particles and the tank in %s\n", p.size(), argv[1]);
    return 0;
  }
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
