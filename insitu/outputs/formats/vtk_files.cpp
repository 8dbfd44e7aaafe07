#include "insitu/outputs/formats/vtk_files.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>
#include <sstream>

#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// In memory, inline binary (base64), zlib-compressed, 64-bit block headers. Not appended data:
// ParaView 5.11's XML reader fails on any appended section (raw or base64) with Debian 12's
// current expat (2.5.0-1+deb12u5); docs/runtime.md has the check and the size cost.
template <class Writer>
std::string write_to_string(Writer& writer, vtkDataObject* data, const char* what) {
  writer->SetInputData(data);
  writer->SetDataModeToBinary();
  writer->SetHeaderTypeToUInt64();
  writer->SetCompressorTypeToZLib();
  writer->WriteToOutputStringOn();
  if (writer->Write() != 1) throw make_error("VTK could not encode the ", what);
  return writer->GetOutputString();
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Whether the points need doubles: the spheres are measured from a point away from the world's
// origin.
bool double_points(const std::array<double, 3>& origin) {
  return origin[0] != 0 || origin[1] != 0 || origin[2] != 0;
}

}  // namespace

std::string vtp_document(std::span<const ParticleSphere> particles,
                         std::span<const AttributeSpan> attributes,
                         const std::array<double, 3>& origin) {
  check_attributes(attributes, particles.size());
  const vtkIdType n = static_cast<vtkIdType>(particles.size());
  vtkNew<vtkPoints> points;
  if (double_points(origin)) points->SetDataTypeToDouble();
  else points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  radius->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    const ParticleSphere& p = particles[static_cast<std::size_t>(i)];
    points->SetPoint(i, origin[0] + p.x, origin[1] + p.y, origin[2] + p.z);
    radius->SetValue(i, p.radius);
  }
  // One vertex per point, so that ParaView shows the points in every representation.
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, i);
  for (vtkIdType i = 0; i < n; ++i) connectivity->SetValue(i, i);
  vertices->SetData(offsets, connectivity);

  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetVerts(vertices);
  poly->GetPointData()->AddArray(radius);
  for (const AttributeSpan& a : attributes) {
    vtkNew<vtkFloatArray> array;
    array->SetName(std::string(a.name).c_str());
    array->SetNumberOfComponents(a.components);
    array->SetNumberOfTuples(n);
    std::copy(a.values.begin(), a.values.end(), array->GetPointer(0));
    poly->GetPointData()->AddArray(array);
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  return write_to_string(writer, poly, "particles (.vtp)");
}

std::string vti_document(const CellStatesView& cells) {
  if (cells.empty()) throw make_error("no cell states to write (empty grid)");
  if (!(cells.cell_size > 0))
    throw make_error("cell states with cell size ", cells.cell_size, " (must be positive)");
  vtkNew<vtkImageData> image;
  image->SetDimensions(cells.dims[0] + 1, cells.dims[1] + 1, cells.dims[2] + 1);
  image->SetOrigin(cells.origin[0], cells.origin[1], cells.origin[2]);
  image->SetSpacing(cells.cell_size, cells.cell_size, cells.cell_size);
  vtkNew<vtkUnsignedCharArray> state;
  state->SetName("state");
  state->SetNumberOfTuples(static_cast<vtkIdType>(cells.cell_count()));
  // Both x-fastest: the view's layout is VTK's cell order.
  std::copy(cells.states, cells.states + cells.cell_count(), state->GetPointer(0));
  image->GetCellData()->AddArray(state);
  image->GetCellData()->SetActiveScalars("state");
  vtkNew<vtkXMLImageDataWriter> writer;
  return write_to_string(writer, image, "cell states (.vti)");
}

void write_vtp(const std::filesystem::path& path, std::span<const ParticleSphere> particles,
               std::span<const AttributeSpan> attributes, bool sync,
               const std::array<double, 3>& origin) {
  write_file_atomically(path, vtp_document(particles, attributes, origin), sync);
}

void write_vti(const std::filesystem::path& path, const CellStatesView& cells, bool sync) {
  write_file_atomically(path, vti_document(cells), sync);
}

std::string PvdSeries::document(std::span<const Entry> entries) {
  std::ostringstream s;
  s.precision(17);
  s << "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       "  <Collection>\n";
  for (const Entry& e : entries)
    s << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\""
      << xml_escape(e.file) << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  return s.str();
}

void PvdSeries::add(double time, std::string file) {
  entries_.push_back({time, std::move(file)});
  write_file_atomically(path_, document(entries_), sync_);
}

std::string pvtp_document(std::span<const std::string> pieces,
                          std::span<const AttributeSpan> attributes,
                          const std::array<double, 3>& origin) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n"
       "  <PPolyData GhostLevel=\"0\">\n"
       "    <PPointData>\n"
       "      <PDataArray type=\"Float32\" Name=\"radius\"/>\n";
  for (const AttributeSpan& a : attributes)
    s << "      <PDataArray type=\"Float32\" Name=\"" << xml_escape(std::string(a.name))
      << "\" NumberOfComponents=\"" << a.components << "\"/>\n";
  s << "    </PPointData>\n"
       "    <PPoints>\n"
       "      <PDataArray type=\""
    << (double_points(origin) ? "Float64" : "Float32")
    << "\" NumberOfComponents=\"3\"/>\n"
       "    </PPoints>\n";
  for (const std::string& piece : pieces)
    s << "    <Piece Source=\"" << xml_escape(piece) << "\"/>\n";
  s << "  </PPolyData>\n</VTKFile>\n";
  return s.str();
}

}  // namespace voxspan
