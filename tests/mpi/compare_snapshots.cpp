// compare_snapshots ONE MANY: the snapshots of an MPI run (MANY) against one process's (ONE):
// the OpenVDB file of each step holds the same fluid (level-set volume and active voxels), and
// each step's particles.pvtp, read with VTK's parallel reader as ParaView reads it, holds the
// same boundary particles with the same arrays as the one process's .vtp; no VTK file has an
// appended-data section. Exit status 1 when anything differs.
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>

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
  if (compared == 0) std::printf("FAIL %s: no snapshots\n", one.c_str());
  return ok && compared > 0 ? 0 : 1;
}
