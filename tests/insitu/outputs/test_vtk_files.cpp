// VTK files read back with VTK's own XML readers; the .pvd series parsed with VTK's XML parser.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include "insitu/io/particle_data.h"
#include "insitu/outputs/formats/vtk_files.h"
#include "tests/support/temp_folder.h"
#include "tools/scenes/lattice.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

TEST(VtkFiles, ParticlesOpenWithVtkWithRadiusAndAttributes) {
  test::TempFolder dir;
  std::vector<ParticleSphere> p = {{0, 0, 0, 0.5f}, {1, 2, 3, 0.25f}, {-1, 0.5f, 2, 1}};
  std::vector<float> pressure = {10, 20, 30};
  std::vector<float> velocity = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::vector<AttributeSpan> attributes = {{"pressure", 1, pressure}, {"velocity", 3, velocity}};
  write_vtp(dir / "p.vtp", p, attributes);
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir / "p.vtp").c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  ASSERT_EQ(poly->GetNumberOfPoints(), 3);
  EXPECT_EQ(poly->GetNumberOfVerts(), 3);
  double x[3];
  poly->GetPoint(1, x);
  EXPECT_DOUBLE_EQ(x[2], 3);
  vtkDataArray* radius = poly->GetPointData()->GetArray("radius");
  ASSERT_NE(radius, nullptr);
  EXPECT_FLOAT_EQ(float(radius->GetComponent(1, 0)), 0.25f);
  vtkDataArray* pr = poly->GetPointData()->GetArray("pressure");
  ASSERT_NE(pr, nullptr);
  EXPECT_FLOAT_EQ(float(pr->GetComponent(2, 0)), 30);
  vtkDataArray* v = poly->GetPointData()->GetArray("velocity");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->GetNumberOfComponents(), 3);
  EXPECT_FLOAT_EQ(float(v->GetComponent(1, 1)), 1);

  // Our own reader (the offline renderer's) gets the same back.
  ParticleData data = read_particles(dir / "p.vtp");
  ASSERT_EQ(data.size(), 3u);
  EXPECT_EQ(data.radii, (std::vector<float>{0.5f, 0.25f, 1}));
  ASSERT_NE(data.attribute("velocity"), nullptr);
  EXPECT_EQ(data.attribute("velocity")->values, velocity);
  EXPECT_EQ(data.attribute("pressure")->values, pressure);
}

// ParaView 5.11's XML reader fails on any <AppendedData> section (raw or base64) with Debian
// 12's current expat, while VTK 9.1's reads it: our documents carry their arrays inline, each
// as zlib-compressed binary, and still read back (the tests above and below).
TEST(VtkFiles, DocumentsHaveNoAppendedSectionParaView511CannotParse) {
  std::vector<ParticleSphere> p = {{0, 0, 0, 0.5f}, {1, 2, 3, 0.25f}};
  std::vector<float> density = {1000, 1001};
  std::vector<AttributeSpan> attributes = {{"density", 1, density}};
  test::LatticeScene scene = test::make_lattice_block(4, 0.1, 0.05f);
  for (const std::string& doc : {vtp_document(p, attributes), vti_document(scene.cells())}) {
    EXPECT_EQ(doc.find("<AppendedData"), std::string::npos) << doc.substr(0, 400);
    EXPECT_EQ(doc.find("format=\"appended\""), std::string::npos) << doc.substr(0, 400);
    EXPECT_NE(doc.find("format=\"binary\""), std::string::npos) << doc.substr(0, 400);
    EXPECT_NE(doc.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  }
}

TEST(VtkFiles, MismatchedAttributesAreRefused) {
  std::vector<ParticleSphere> p(2);
  std::vector<float> few = {1};
  std::vector<AttributeSpan> attributes = {{"density", 1, few}};
  try {
    vtp_document(p, attributes);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("attribute \"density\" has 1 values for 2 particles"),
              std::string::npos)
        << e.what();
  }
}

TEST(VtkFiles, CellStatesOpenWithVtkInTheirGrid) {
  test::TempFolder dir;
  test::LatticeScene scene = test::make_lattice_block(8, 0.1, 0.05f);
  write_vti(dir / "c.vti", scene.cells());
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "c.vti").c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], scene.dims[0] + 1);
  EXPECT_EQ(dims[2], scene.dims[2] + 1);
  double spacing[3], origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  EXPECT_DOUBLE_EQ(spacing[1], scene.cell_size);
  EXPECT_DOUBLE_EQ(origin[0], scene.origin[0]);
  vtkDataArray* state = image->GetCellData()->GetArray("state");
  ASSERT_NE(state, nullptr);
  ASSERT_EQ(std::size_t(state->GetNumberOfTuples()), scene.states.size());
  for (std::size_t c = 0; c < scene.states.size(); ++c)
    ASSERT_EQ(int(state->GetComponent(vtkIdType(c), 0)), scene.states[c]) << c;
  EXPECT_GT(scene.count_state(cell::kInnerFull), 0u);
  EXPECT_THROW(vti_document(CellStatesView{}), Error);
}

TEST(VtkFiles, SeriesListsEveryFileAndStaysValidXml) {
  test::TempFolder dir;
  PvdSeries series(dir / "particles.pvd");
  std::vector<ParticleSphere> p = {{0, 0, 0, 1}};
  for (int step = 0; step < 3; ++step) {
    std::string name = "particles_" + std::to_string(step) + ".vtp";
    write_vtp(dir / name, p, {});
    series.add(0.5 * step, name);
  }
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName((dir / "particles.pvd").c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement* root = parser->GetRootElement();
  ASSERT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* collection = root->GetNestedElement(0);
  ASSERT_EQ(collection->GetNumberOfNestedElements(), 3);
  for (int i = 0; i < 3; ++i) {
    vtkXMLDataElement* set = collection->GetNestedElement(i);
    EXPECT_DOUBLE_EQ(std::stod(set->GetAttribute("timestep")), 0.5 * i);
    std::filesystem::path file = dir / set->GetAttribute("file");
    vtkNew<vtkXMLPolyDataReader> reader;
    EXPECT_TRUE(reader->CanReadFile(file.c_str())) << file;
  }
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);
}

}  // namespace
}  // namespace voxspan
