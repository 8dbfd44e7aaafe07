// Particles from VTK files: XML (.vtp, .vtu) and legacy (.vtk: polydata or an unstructured grid,
// as DualSPHysics' PartVTK writes them): the points, a radius array if there is one, and every
// 1- or 3-component point-data array as a named attribute.
#include <vtkDataArray.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <fstream>
#include <string>

#include "insitu/io/particle_data.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

template <class Reader>
vtkSmartPointer<vtkPointSet> read_point_set(const std::filesystem::path& path) {
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  if (!reader->CanReadFile(path.c_str()))
    throw make_error("cannot read particles from ", path.string(),
                     ": not a readable VTK XML file of this type");
  reader->Update();
  if (reader->GetErrorCode() != 0 || !reader->GetOutput())
    throw make_error("cannot read particles from ", path.string(), ": VTK reader failed");
  return vtkSmartPointer<vtkPointSet>(reader->GetOutput());
}

vtkSmartPointer<vtkPointSet> read_legacy_point_set(const std::filesystem::path& path) {
  // Its first line says what it is; VTK's reader would print its own error too.
  std::string first;
  std::getline(std::ifstream(path), first);
  if (!first.starts_with("# vtk DataFile"))
    throw make_error("cannot read particles from ", path.string(),
                     ": not a legacy VTK file (its first line is not \"# vtk DataFile ...\")");
  vtkNew<vtkGenericDataObjectReader> reader;
  reader->SetFileName(path.c_str());
  // The type from the header alone, so that a file of another kind reads nothing.
  const int type = reader->ReadOutputType();
  if (type != VTK_POLY_DATA && type != VTK_UNSTRUCTURED_GRID)
    throw make_error("cannot read particles from ", path.string(),
                     type < 0 ? ": not a legacy VTK file"
                              : ": a legacy VTK file of other data than points (polydata or an "
                                "unstructured grid)");
  reader->Update();
  auto* set = vtkPointSet::SafeDownCast(reader->GetOutput());
  if (reader->GetErrorCode() != 0 || set == nullptr)
    throw make_error("cannot read particles from ", path.string(), ": VTK reader failed");
  return vtkSmartPointer<vtkPointSet>(set);
}

vtkSmartPointer<vtkPointSet> read_any_point_set(const std::filesystem::path& path) {
  const std::string ext = extension_of(path);
  if (ext == ".vtk") return read_legacy_point_set(path);
  if (ext == ".vtu") return read_point_set<vtkXMLUnstructuredGridReader>(path);
  return read_point_set<vtkXMLPolyDataReader>(path);
}

}  // namespace

ParticleData read_vtk_particles(const std::filesystem::path& path) {
  require_particle_file(path);
  vtkSmartPointer<vtkPointSet> set = read_any_point_set(path);
  ParticleData data;
  const vtkIdType n = set->GetNumberOfPoints();
  data.positions.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) set->GetPoint(i, data.positions[std::size_t(i)].data());
  vtkPointData* pd = set->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = pd->GetArray(a);  // null for non-numeric arrays
    if (!array || !array->GetName()) continue;
    int components = array->GetNumberOfComponents();
    if (components != 1 && components != 3) continue;
    Attribute attribute{array->GetName(), components, {}};
    attribute.values.resize(static_cast<std::size_t>(n) * std::size_t(components));
    for (vtkIdType i = 0; i < n; ++i)
      for (int c = 0; c < components; ++c)
        attribute.values[std::size_t(i) * std::size_t(components) + std::size_t(c)] =
            static_cast<float>(array->GetComponent(i, c));
    data.attributes.push_back(std::move(attribute));
  }
  adopt_radius_attribute(data);
  return data;
}

}  // namespace voxspan
