// compare_snapshots ONE MANY: the snapshots of an MPI run (MANY) against one process's (ONE):
// the OpenVDB file of each step holds the same fluid (level-set volume and active voxels),
// each step's particles.pvtp, read with VTK's parallel reader as ParaView reads it, holds the
// same boundary particles with the same arrays as the one process's .vtp, and each step's
// cells.vti the same cell states; every file cells.pvd lists exists; no VTK file has an
// appended-data section. Exit status 1 when anything differs.
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "output_files.h"

namespace fs = std::filesystem;

namespace {

bool same_vdb(const fs::path& one, const fs::path& many) {
  const voxspan::test::VdbContents a = voxspan::test::read_vdb(one),
                                   b = voxspan::test::read_vdb(many);
  const bool ok = a.ok && b.ok && a.grids == b.grids &&
                  std::abs(a.fluid_volume - b.fluid_volume) <= 1e-9 * std::abs(a.fluid_volume);
  std::printf("%s %s: volume %.9g against %.9g\n", ok ? "ok  " : "FAIL", many.c_str(),
              b.fluid_volume, a.fluid_volume);
  return ok;
}

bool same_particles(const fs::path& one_vtp, const fs::path& many_pvtp) {
  const voxspan::test::VtpContents a = voxspan::test::read_vtp(one_vtp);
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName(many_pvtp.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  const long long points = poly != nullptr ? poly->GetNumberOfPoints() : -1;
  bool ok = a.ok && !a.appended_data && reader->GetErrorCode() == 0 && points == a.points;
  for (const std::string& name : a.arrays)
    ok = ok && poly->GetPointData()->GetArray(name.c_str()) != nullptr;
  for (const auto& e : fs::directory_iterator(many_pvtp.parent_path()))
    ok = ok && !voxspan::test::has_appended_data(e.path());
  std::printf("%s %s: %lld points against %lld\n", ok ? "ok  " : "FAIL", many_pvtp.c_str(), points,
              static_cast<long long>(a.points));
  return ok;
}

bool same_cells(const fs::path& one_vti, const fs::path& many_vti) {
  const voxspan::test::VtiContents a = voxspan::test::read_vti(one_vti),
                                   b = voxspan::test::read_vti(many_vti);
  const bool ok =
      a.ok && b.ok && a.has_state && a.states == b.states && std::equal(a.dims, a.dims + 3, b.dims);
  std::size_t differ = 0;
  for (std::size_t c = 0; c < std::min(a.states.size(), b.states.size()); ++c)
    differ += a.states[c] != b.states[c];
  std::printf("%s %s: %zu cells, %zu states differ\n", ok ? "ok  " : "FAIL", many_vti.c_str(),
              b.states.size(), differ);
  return ok;
}

bool series_files_exist(const fs::path& pvd) {
  bool ok = true;
  for (const std::string& file : voxspan::test::pvd_files(pvd))
    if (!fs::exists(pvd.parent_path() / file)) {
      std::printf("FAIL %s lists %s, which is not there\n", pvd.c_str(), file.c_str());
      ok = false;
    }
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: compare_snapshots ONE MANY\n");
    return 2;
  }
  const fs::path one = argv[1], many = argv[2];
  bool ok = true;
  int compared = 0;
  for (const auto& e : fs::directory_iterator(one / "snapshots")) {
    ok = same_vdb(e.path(), many / "snapshots" / e.path().filename()) && ok;
    ++compared;
  }
  for (const auto& e : fs::directory_iterator(one / "vtk")) {
    if (e.path().extension() != ".vtp") continue;
    fs::path pvtp = many / "vtk" / e.path().filename();
    pvtp.replace_extension(".pvtp");
    ok = same_particles(e.path(), pvtp) && ok;
    ++compared;
  }
  for (const auto& e : fs::directory_iterator(one / "vtk"))
    if (e.path().extension() == ".vti") {
      ok = same_cells(e.path(), many / "vtk" / e.path().filename()) && ok;
      ++compared;
    }
  for (const char* series : {"particles.pvd", "cells.pvd"})
    ok = series_files_exist(many / "vtk" / series) && ok;
  if (compared == 0) std::printf("FAIL %s: no snapshots\n", one.c_str());
  return ok && compared > 0 ? 0 : 1;
}
