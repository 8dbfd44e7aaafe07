// Particles from VTK files: XML (.vtp, .vtu) and legacy (.vtk: polydata or an unstructured grid,
// as DualSPHysics' PartVTK writes them): the points, a radius array if there is one, and every
// 1- or 3-component point-data array as a named attribute. A file VTK's readers complain about
// (cut short, corrupt) is refused with their first complaint: VTK would otherwise hand back
// what it read so far, or nothing, and say so only on the terminal.
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cctype>
#include <cstdint>
#include <fstream>
#include <string>
#include <thread>

#include "insitu/io/particle_data.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// Keeps the first error or warning VTK raises while this thread reads a file. Readers, their
// executives and XML parsers raise theirs as events (observed here, so that VTK does not also
// print them); the legacy reader's data parsing (vtkReadASCIIData, its binary twin) only logs
// a generic warning, which vtkLogger hands to the callback registered here for the read.
class Complaints : public vtkCommand {
 public:
  static Complaints* New() { return new Complaints; }
  Complaints() {
    vtkLogger::AddCallback(callback_id_.c_str(), &Complaints::logged, this,
                           vtkLogger::VERBOSITY_WARNING);
  }
  ~Complaints() override { vtkLogger::RemoveCallback(callback_id_.c_str()); }

  void Execute(vtkObject*, unsigned long, void* message) override {
    if (message) keep(static_cast<const char*>(message));
  }
  void listen_to(vtkObject* object) {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }
  // Throws the first complaint, trimmed to its text, naming the file.
  void throw_if_any(const std::filesystem::path& path) const {
    if (first_.empty()) return;
    std::string text = first_;
    // Events begin "ERROR: In file, line N\nvtkClass (0x...): ".
    if (const auto colon = text.find("): "); colon != std::string::npos) text.erase(0, colon + 3);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    throw make_error("cannot read particles from ", path.string(),
                     ": the file is cut short or corrupt (VTK's reader: ", text, ")");
  }

 private:
  static void logged(void* self, const vtkLogger::Message& message) {
    auto* me = static_cast<Complaints*>(self);
    // The callback is the process's: another thread's VTK messages are not this file's.
    if (std::this_thread::get_id() == me->thread_ && message.message) me->keep(message.message);
  }
  // Only ever on the reading thread: logged() filters the others out.
  void keep(const char* message) {
    if (first_.empty()) first_ = message;
  }

  const std::thread::id thread_ = std::this_thread::get_id();
  const std::string callback_id_ =
      "voxspan particle file " + std::to_string(reinterpret_cast<std::uintptr_t>(this));
  std::string first_;
};

template <class Reader>
vtkSmartPointer<vtkPointSet> read_point_set(const std::filesystem::path& path) {
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  if (!reader->CanReadFile(path.c_str()))
    throw make_error("cannot read particles from ", path.string(),
                     ": not a readable VTK XML file of this type");
  vtkNew<Complaints> complaints;
  complaints->listen_to(reader);
  complaints->listen_to(reader->GetExecutive());
  reader->SetReaderErrorObserver(complaints);
  reader->SetParserErrorObserver(complaints);
  reader->Update();
  complaints->throw_if_any(path);
  if (reader->GetErrorCode() != 0 || !reader->GetOutput())
    throw make_error("cannot read particles from ", path.string(), ": VTK reader failed");
  return vtkSmartPointer<vtkPointSet>(reader->GetOutput());
}

// The legacy reader of `type` (polydata or an unstructured grid), set to read every array.
template <class Reader>
vtkSmartPointer<vtkPointSet> read_legacy_points(const std::filesystem::path& path) {
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  // Without these the reader keeps only the first SCALARS and the first VECTORS section:
  // DualSPHysics writes Vel and Ace, Rhop, Press, Mass and Type.
  reader->ReadAllScalarsOn();
  reader->ReadAllVectorsOn();
  reader->ReadAllNormalsOn();
  reader->ReadAllColorScalarsOn();
  reader->ReadAllFieldsOn();
  vtkNew<Complaints> complaints;
  complaints->listen_to(reader);
  complaints->listen_to(reader->GetExecutive());
  reader->Update();
  complaints->throw_if_any(path);
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
  // The type from the header alone, so that a file of another kind reads nothing.
  vtkNew<vtkGenericDataObjectReader> header;
  header->SetFileName(path.c_str());
  const int type = header->ReadOutputType();
  if (type == VTK_POLY_DATA) return read_legacy_points<vtkPolyDataReader>(path);
  if (type == VTK_UNSTRUCTURED_GRID) return read_legacy_points<vtkUnstructuredGridReader>(path);
  throw make_error("cannot read particles from ", path.string(),
                   type < 0 ? ": not a legacy VTK file"
                            : ": a legacy VTK file of other data than points (polydata or an "
                              "unstructured grid)");
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
