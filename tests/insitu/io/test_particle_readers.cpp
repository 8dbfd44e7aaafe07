// Particle files for the offline tools: CSV (ours and ParaView's), XYZ, and HDF5 as PySPH and
// the GADGET family (SWIFT, GIZMO...) write it, written here with the HDF5 C API in their layouts.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "insitu/io/particle_data.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_folder.h"

namespace voxspan {
namespace {

std::string error_of(const std::filesystem::path& path, const ParticleReadOptions& options = {}) {
  return test::error_message([&] { read_particles(path, options); });
}

// The particles of a file `name` in `dir` holding `text`.
ParticleData read_text(const test::TempFolder& dir, const char* name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return read_particles(dir / name);
}

TEST(CsvParticles, HeaderNamesPositionsRadiiScalarsAndVectors) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "p.csv",
                             "# made by a solver\n"
                             "x,y,z,radius,vx,vy,vz,pressure\n"
                             "0,0,0,0.5,1,2,3,100\n"
                             "1.5,-2,3e-2,0.25,4,5,6,200\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][0], 1.5);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 0.03);
  EXPECT_EQ(d.radii, (std::vector<float>{0.5f, 0.25f}));
  ASSERT_EQ(d.attributes.size(), 2u);
  EXPECT_EQ(d.attributes[0].name, "v");
  EXPECT_EQ(d.attributes[0].components, 3);
  EXPECT_EQ(d.attributes[0].values, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(d.attributes[1].name, "pressure");
  EXPECT_EQ(d.spheres(1.f)[1].radius, 0.25f);
}

TEST(CsvParticles, ParaViewExportWithQuotedPointColumns) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "pv.csv",
                             "\"density\",\"velocity:0\",\"velocity:1\",\"velocity:2\","
                             "\"Points:0\",\"Points:1\",\"Points:2\"\n"
                             "1000,0,0,-1,0.1,0.2,0.3\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_DOUBLE_EQ(d.positions[0][2], 0.3);
  EXPECT_TRUE(d.radii.empty());
  ASSERT_NE(d.attribute("velocity"), nullptr);
  EXPECT_EQ(d.attribute("velocity")->values, (std::vector<float>{0, 0, -1}));
  EXPECT_EQ(d.attribute("density")->values, (std::vector<float>{1000}));
  EXPECT_EQ(d.spheres(0.1f)[0].radius, 0.1f);
}

// numpy.savetxt(path, a, header="x y z u v w") writes its header as a comment and white space
// between the numbers.
TEST(CsvParticles, NumpysHeaderInACommentAndWhiteSpace) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "np.csv",
                             "# x y z u v w\n"
                             "0.0 0.0 0.0 1.0 2.0 3.0\n"
                             "1.5e-1\t2 3 4 5 6\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][0], 0.15);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 3);
  ASSERT_NE(d.attribute("velocity"), nullptr);  // u, v, w
  EXPECT_EQ(d.attribute("velocity")->values, (std::vector<float>{1, 2, 3, 4, 5, 6}));

  d = read_text(dir, "tabs.csv", "X\tY\tZ\tp\n1\t2\t3\t4\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_DOUBLE_EQ(d.positions[0][1], 2);
  EXPECT_EQ(d.attribute("p")->values, (std::vector<float>{4}));
}

// numpy.savetxt(path, a, delimiter=",") with no header: x, y, z first, as in .xyz files, and
// said; a comment before the numbers that names fewer columns than they have is not a header.
TEST(CsvParticles, WithoutAHeaderTheFirstColumnsAreThePositions) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "bare.csv", "1,2,3\n4,5,6\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 6);
  EXPECT_TRUE(d.attributes.empty());
  EXPECT_EQ(d.chosen, "columns 1 to 3 as x, y, z (no header row names them)");
  d = read_text(dir, "savetxt.txt", "1.0 2.0 3.0\n4.0 5.0 6.0\n");  // numpy.savetxt's default
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[0][1], 2);
  d = read_text(dir, "more.csv", "# x y\n1 2 3 7 8\n");
  ASSERT_EQ(d.size(), 1u);
  ASSERT_NE(d.attribute("column5"), nullptr);
  EXPECT_EQ(d.attribute("column5")->values, (std::vector<float>{8}));
  EXPECT_EQ(d.chosen,
            "columns 1 to 3 as x, y, z (no header row names them), the others as column4..");
}

// As pandas and Excel write tables: x, y, z apart in any order, Excel's byte-order mark, pandas'
// unnamed index column and its NaN as an empty field (the last one too).
TEST(CsvParticles, PandasAndExcelTables) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "excel.csv", "\xEF\xBB\xBFrho,z,y,x\n1000,3,2,1\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_DOUBLE_EQ(d.positions[0][0], 1);
  EXPECT_DOUBLE_EQ(d.positions[0][2], 3);
  ASSERT_EQ(d.attributes.size(), 1u);
  EXPECT_EQ(d.attributes[0].name, "rho");
  d = read_text(dir, "pandas.csv", ",x,y,z,p\n0,0.0,0.0,0.0,\n1,1,,1,2\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_TRUE(std::isnan(d.positions[1][1]));  // left out, counted, by the pipeline
  ASSERT_NE(d.attribute("p"), nullptr);
  EXPECT_TRUE(std::isnan(d.attribute("p")->values[0]));
  EXPECT_EQ(d.attribute("p")->values[1], 2.f);
  ASSERT_NE(d.attribute("column1"), nullptr);
  EXPECT_EQ(d.attribute("column1")->values, (std::vector<float>{0, 1}));
}

// DualSPHysics' CSV: semicolons, a unit after each name, a semicolon ending every row.
// A 2D run's table has x and y alone: z is 0, and the reader says so.
TEST(CsvParticles, XAndYAloneAreA2DRun) {
  test::TempFolder dir;
  const ParticleData d = read_text(dir, "flat.csv", "x,y,p\n1,2,10\n3,4,20\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][1], 4);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 0);
  EXPECT_EQ(d.attribute("p")->values, (std::vector<float>{10, 20}));
  EXPECT_EQ(d.chosen, "no z column: read as a 2D run in the x-y plane (z = 0)");
  std::ofstream(dir / "x.csv") << "x,p\n1,2\n";
  EXPECT_NE(error_of(dir / "x.csv").find("no position columns"), std::string::npos);
}

// PySPH's u, v, w columns are its velocity, as in its HDF5 files.
TEST(CsvParticles, UVWColumnsAreTheVelocity) {
  test::TempFolder dir;
  const ParticleData d = read_text(dir, "p.csv", "x,y,z,u,v,w,rho\n0,0,0,1,2,3,1000\n");
  ASSERT_NE(d.attribute("velocity"), nullptr);
  EXPECT_EQ(d.attribute("velocity")->components, 3);
  EXPECT_EQ(d.attribute("velocity")->values, (std::vector<float>{1, 2, 3}));
  EXPECT_NE(d.attribute("rho"), nullptr);
}

TEST(CsvParticles, SemicolonsUnitsAndDottedVectors) {
  test::TempFolder dir;
  ParticleData d = read_text(
      dir, "part.csv",
      "Pos.x [m];Pos.y [m];Pos.z [m];Idp;Vel.x [m/s];Vel.y [m/s];Vel.z [m/s];Rhop [kg/m^3];\n"
      "0.1;0.2;0.3;7;1;2;3;1000;\n"
      "0.4;0.5;0.6;8;4;5;6;1001;\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 0.6);
  ASSERT_NE(d.attribute("Vel"), nullptr);
  EXPECT_EQ(d.attribute("Vel")->components, 3);
  EXPECT_EQ(d.attribute("Vel")->values, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  ASSERT_NE(d.attribute("Rhop"), nullptr);
  EXPECT_EQ(d.attribute("Rhop")->values, (std::vector<float>{1000, 1001}));
  EXPECT_NE(d.attribute("Idp"), nullptr);

  // A bracket right after the name is a component, not a unit.
  d = read_text(dir, "f.csv", "x (m);y (m);z (m);f[0];f[1];f[2]\n1;2;3;4;5;6\n");
  EXPECT_DOUBLE_EQ(d.positions[0][1], 2);
  ASSERT_NE(d.attribute("f"), nullptr);
  EXPECT_EQ(d.attribute("f")->values, (std::vector<float>{4, 5, 6}));
}

// Legacy VTK, as DualSPHysics' PartVTK writes its particles: polydata with vertices and point
// data (a vector and scalars); an unstructured grid reads alike; other data is refused.
TEST(LegacyVtkParticles, PolyDataAndUnstructuredGridPointsWithTheirArrays) {
  test::TempFolder dir;
  const std::string data =
      "POINT_DATA 2\n"
      "VECTORS Vel float\n1 2 3 4 5 6\n"
      "SCALARS Rhop float 1\nLOOKUP_TABLE default\n1000 1001\n";
  ParticleData d = read_text(dir, "PartFluid_0000.vtk",
                             "# vtk DataFile Version 3.0\nPart_0000\nASCII\nDATASET POLYDATA\n"
                             "POINTS 2 float\n0 0 0 0.1 0.2 0.3\nVERTICES 2 4\n1 0\n1 1\n" +
                                 data);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NEAR(d.positions[1][1], 0.2, 1e-7);
  ASSERT_NE(d.attribute("Vel"), nullptr);
  EXPECT_EQ(d.attribute("Vel")->components, 3);
  EXPECT_EQ(d.attribute("Vel")->values, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  ASSERT_NE(d.attribute("Rhop"), nullptr);
  EXPECT_EQ(d.attribute("Rhop")->values, (std::vector<float>{1000, 1001}));

  d = read_text(dir, "grid.VTK",
                "# vtk DataFile Version 3.0\ngrid\nASCII\n"
                "DATASET UNSTRUCTURED_GRID\nPOINTS 2 double\n0 0 0 1 1 1\n"
                "CELLS 2 4\n1 0\n1 1\nCELL_TYPES 2\n1\n1\n" +
                    data);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 1);
  EXPECT_EQ(d.attribute("Rhop")->values, (std::vector<float>{1000, 1001}));

  std::ofstream(dir / "image.vtk") << "# vtk DataFile Version 3.0\nimage\nASCII\n"
                                      "DATASET STRUCTURED_POINTS\nDIMENSIONS 2 1 1\n"
                                      "SPACING 1 1 1\nORIGIN 0 0 0\n";
  EXPECT_NE(error_of(dir / "image.vtk").find("image.vtk: a legacy VTK file of other data"),
            std::string::npos);
  std::ofstream(dir / "text.vtk") << "not VTK at all\n";
  EXPECT_NE(error_of(dir / "text.vtk").find("text.vtk: not a legacy VTK file"), std::string::npos);
}

// DualSPHysics writes several sections of each kind (Vel and Ace; Type, Rhop, Press): every one
// is read, not only the first SCALARS and the first VECTORS, which is all VTK reads by default.
TEST(LegacyVtkParticles, EverySectionOfEachKindIsRead) {
  test::TempFolder dir;
  ParticleData d =
      read_text(dir, "PartFluid_0001.vtk",
                "# vtk DataFile Version 3.0\nPart_0001\nASCII\nDATASET POLYDATA\n"
                "POINTS 2 float\n0 0 0 0.1 0.2 0.3\nPOINT_DATA 2\n"
                "SCALARS Type unsigned_char 1\nLOOKUP_TABLE default\n2 2\n"
                "VECTORS Vel float\n1 2 3 4 5 6\nVECTORS Ace float\n0 0 -9.8 0 0 -9.8\n"
                "SCALARS Rhop float 1\nLOOKUP_TABLE default\n1000 1001\n"
                "SCALARS Press float 1\nLOOKUP_TABLE default\n10 20\n");
  for (const char* name : {"Type", "Vel", "Ace", "Rhop", "Press"})
    EXPECT_NE(d.attribute(name), nullptr) << name;
  ASSERT_NE(d.attribute("Press"), nullptr);
  EXPECT_EQ(d.attribute("Press")->values, (std::vector<float>{10, 20}));
  EXPECT_EQ(d.attribute("Ace")->components, 3);
}

// A file cut short is refused with VTK's reason, not rendered from what was read before the cut
// (legacy ASCII and binary) or as an empty set (XML).
TEST(VtkParticles, FilesCutShortAreRefused) {
  test::TempFolder dir;
  const auto expect_refused = [&](const char* name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    const std::string e = error_of(dir / name);
    EXPECT_NE(e.find(std::string(name) + ": the file is cut short or corrupt (VTK's reader: "),
              std::string::npos)
        << e;
  };
  expect_refused("ascii.vtk",
                 "# vtk DataFile Version 3.0\ncut\nASCII\nDATASET POLYDATA\n"
                 "POINTS 4 float\n0 0 0 1 1 1 2");
  // Binary: big-endian floats, of which the cut leaves 7 of 12.
  std::string binary =
      "# vtk DataFile Version 3.0\ncut\nBINARY\nDATASET POLYDATA\n"
      "POINTS 4 float\n";
  binary.append(7 * 4, '\x3f');
  expect_refused("binary.vtk", binary);
  expect_refused("cut.vtp",
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" "
                 "byte_order=\"LittleEndian\">\n<PolyData>\n<Piece NumberOfPoints=\"2\" "
                 "NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                 "NumberOfPolys=\"0\">\n<Points>\n<DataArray type=\"Float32\" "
                 "NumberOfComponents=\"3\" format=\"ascii\">\n0 0 0 1 1");
}

// A series' files carry their steps in their names; a file whose format stores none takes it.
TEST(ParticleFiles, TheNumberEndingANameIsTheStep) {
  EXPECT_EQ(step_in_name("out/PartFluid_0050.vtk"), 50);
  EXPECT_EQ(step_in_name("ParticleData_Fluid_10.vtk"), 10);
  EXPECT_EQ(step_in_name("fluid0007.csv"), 7);
  EXPECT_EQ(step_in_name("particles.csv"), std::nullopt);
  EXPECT_EQ(step_in_name("run2/particles.csv"), std::nullopt);
  EXPECT_EQ(step_in_name("f_1234567890123456789.csv"), std::nullopt);  // past int64
  test::TempFolder dir;
  EXPECT_EQ(read_text(dir, "block_0042.csv", "x,y,z\n0,0,0\n").step, 42);
  EXPECT_EQ(read_text(dir, "block.csv", "x,y,z\n0,0,0\n").step, std::nullopt);
}

TEST(CsvParticles, ErrorsNameFileAndLine) {
  test::TempFolder dir;
  std::ofstream(dir / "a.csv") << "1,2\n";
  EXPECT_NE(error_of(dir / "a.csv")
                .find("a.csv:1: the first row holds 2 numbers and no header row names them"),
            std::string::npos);
  std::ofstream(dir / "b.csv") << "x,y,z\n1,2,3\n1,2\n";
  EXPECT_NE(error_of(dir / "b.csv").find("b.csv:3: 2 fields; the header has 3"), std::string::npos);
  std::ofstream(dir / "c.csv") << "x,y,z\n1,2,abc\n";
  EXPECT_NE(error_of(dir / "c.csv").find("c.csv:2: column \"z\" is not a number: \"abc\""),
            std::string::npos);
  std::ofstream(dir / "d.csv") << "a,b\n1,2\n";
  EXPECT_NE(error_of(dir / "d.csv").find("no position columns"), std::string::npos);
  EXPECT_NE(error_of(dir / "none.csv").find("none.csv: no such file"), std::string::npos);
  EXPECT_NE(error_of(dir / "x.obj").find("unknown extension \".obj\""), std::string::npos);
}

// PySPH's arrays (--arrays fluid) name parts of a PySPH file; the other formats have none, and
// reading the whole file instead would render the walls the caller meant to leave out.
TEST(CsvParticles, NamedArraysAreAnErrorOutsideHdf5Files) {
  test::TempFolder dir;
  std::ofstream(dir / "p.csv") << "x,y,z\n0,0,0\n";
  std::ofstream(dir / "p.xyz") << "0 0 0\n";
  EXPECT_EQ(error_of(dir / "p.csv", {{"fluid"}, {}}),
            "cannot read particles from " + (dir / "p.csv").string() +
                ": particle arrays were named (fluid), but only HDF5 files (.hdf5 .h5: PySPH's "
                "arrays, GADGET's particle types) have named arrays; a .csv file is one set of "
                "particles");
  EXPECT_NE(error_of(dir / "p.xyz", {{"fluid", "wall"}, {}}).find("named (fluid, wall)"),
            std::string::npos);
  EXPECT_EQ(read_particles(dir / "p.csv", {{"all"}, {}}).size(), 1u);  // all of it: what it holds
}

TEST(XyzParticles, PlainAndExtended) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "p.xyz", "# x y z r\n0 0 0 0.5\n1 2 3 0.25\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.radii, (std::vector<float>{0.5f, 0.25f}));
  d = read_text(dir, "e.xyz", "3\ncomment line\nO 0 0 0\nH 1 0 0\nH 0 1 0\n");
  ASSERT_EQ(d.size(), 3u);
  EXPECT_TRUE(d.radii.empty());
  EXPECT_DOUBLE_EQ(d.positions[2][1], 1);
  std::ofstream(dir / "w.xyz") << "2\n\n0 0 0\n";
  EXPECT_NE(error_of(dir / "w.xyz").find("header says 2 particles; the file has 1"),
            std::string::npos);
  std::ofstream(dir / "x.xyz") << "0 0 0 1 7\n1 1 1\n";
  EXPECT_NE(error_of(dir / "x.xyz").find("x.xyz:2: 3 columns; earlier lines have 5"),
            std::string::npos);
}

// Extended XYZ's Properties= (ASE, OVITO) names the columns: positions, radii and attributes
// where it says, strings skipped; without it a fourth column would read as the radius.
TEST(XyzParticles, PropertiesNameTheColumns) {
  test::TempFolder dir;
  ParticleData d = read_text(dir, "p.xyz",
                             "2\nLattice=\"1 0 0 0 1 0 0 0 1\" Properties=species:S:1:pos:R:3:"
                             "rho:R:1:vel:R:3:radius:R:1 time=0.5\n"
                             "H 0 0 0 1000 1 2 3 0.01\nH 1 2 3 1001 4 5 6 0.02\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 3);
  EXPECT_EQ(d.radii, (std::vector<float>{0.01f, 0.02f}));
  ASSERT_NE(d.attribute("rho"), nullptr);
  EXPECT_EQ(d.attribute("rho")->values, (std::vector<float>{1000, 1001}));
  ASSERT_NE(d.attribute("vel"), nullptr);
  EXPECT_EQ(d.attribute("vel")->components, 3);
  EXPECT_EQ(d.attribute("vel")->values[3], 4.f);
  std::ofstream(dir / "bad.xyz") << "1\nProperties=species:S:1:rho:R:1\nH 1\n";
  EXPECT_NE(error_of(dir / "bad.xyz").find("bad.xyz:2: Properties= names no pos:R:3 column"),
            std::string::npos)
      << error_of(dir / "bad.xyz");
  std::ofstream(dir / "odd.xyz") << "1\nProperties=pos:R\n0 0 0\n";
  EXPECT_NE(error_of(dir / "odd.xyz").find("odd.xyz:2: Properties=pos:R: not name:type:count"),
            std::string::npos)
      << error_of(dir / "odd.xyz");
}

// ---- PySPH ----

void write_dataset(hid_t group, const char* name, const std::vector<double>& values,
                   bool stored = true) {
  hsize_t n = values.size();
  hid_t space = H5Screate_simple(1, &n, nullptr);
  hid_t set = H5Dcreate2(group, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (n > 0) H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  // PySPH's per-property attributes: stored (numpy's bool, which h5py writes as an enum over
  // int8), name, type, default.
  hid_t scalar = H5Screate(H5S_SCALAR);
  hid_t boolean = H5Tenum_create(H5T_NATIVE_SCHAR);
  const signed char no = 0, yes = 1;
  H5Tenum_insert(boolean, "FALSE", &no);
  H5Tenum_insert(boolean, "TRUE", &yes);
  hid_t flag = H5Acreate2(set, "stored", boolean, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(flag, boolean, stored ? &yes : &no);
  H5Aclose(flag);
  H5Tclose(boolean);
  hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, std::strlen(name));
  hid_t attr = H5Acreate2(set, "name", text, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, text, name);
  H5Aclose(attr);
  H5Tclose(text);
  H5Sclose(scalar);
  H5Dclose(set);
  H5Sclose(space);
}

void write_array(hid_t particles, const char* name, const std::vector<std::array<double, 3>>& xyz,
                 bool three_d, const std::vector<std::string>& extra, bool still = false) {
  hid_t g = H5Gcreate2(particles, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t arrays = H5Gcreate2(g, "arrays", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t constants = H5Gcreate2(g, "constants", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  std::vector<double> x, y, z, u, v, w, m, rho;
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    x.push_back(xyz[i][0]), y.push_back(xyz[i][1]), z.push_back(xyz[i][2]);
    u.push_back(still ? 0.0 : 1.0 + i), v.push_back(still ? 0.0 : 2.0),
        w.push_back(still ? 0.0 : -1.0), m.push_back(0.001), rho.push_back(1000 + i);
  }
  write_dataset(arrays, "x", x);
  write_dataset(arrays, "y", y);
  if (three_d) write_dataset(arrays, "z", z);
  write_dataset(arrays, "u", u);
  write_dataset(arrays, "v", v);
  if (three_d) write_dataset(arrays, "w", w);
  write_dataset(arrays, "m", m);
  write_dataset(arrays, "rho", rho);
  write_dataset(arrays, "au", {}, /*stored=*/false);  // declared, not output
  for (const std::string& e : extra)
    write_dataset(arrays, e.c_str(), std::vector<double>(xyz.size(), 7.0));
  write_dataset(constants, "c0", {10.0});
  H5Gclose(constants);
  H5Gclose(arrays);
  H5Gclose(g);
}

void write_pysph_file(const std::filesystem::path& path) {
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t solver = H5Gcreate2(f, "solver_data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t scalar = H5Screate(H5S_SCALAR);
  double t = 0.75;
  long long count = 1500;
  hid_t a = H5Acreate2(solver, "t", H5T_IEEE_F64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, &t);
  H5Aclose(a);
  a = H5Acreate2(solver, "count", H5T_STD_I64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_LLONG, &count);
  H5Aclose(a);
  H5Sclose(scalar);
  H5Gclose(solver);
  hid_t particles = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_array(particles, "fluid", {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0.1, 0.3}}, true, {"p"});
  write_array(particles, "solid", {{-1, -1, -1}, {-2, -2, -2}}, true, {});
  H5Gclose(particles);
  H5Fclose(f);
}

// Offline frames are numbered by the file's own step (PySPH's iteration count), still rising
// where files say none or go back.
TEST(PySphParticles, OfflineStepsAreTheFilesOwn) {
  test::TempFolder dir;
  write_pysph_file(dir / "dam_break_1500.hdf5");
  const ParticleData pysph = read_particles(dir / "dam_break_1500.hdf5");
  EXPECT_EQ(pysph.step_after(-1), 1500);
  EXPECT_EQ(pysph.step_after(1499), 1500);
  EXPECT_EQ(pysph.step_after(1500), 1501);  // not back, nor twice
  const ParticleData none;
  EXPECT_EQ(none.step_after(-1), 0);
  EXPECT_EQ(none.step_after(1500), 1501);
}

TEST(PySphParticles, ReadsEveryArrayWithTimeStepAndCommonProperties) {
  test::TempFolder dir;
  write_pysph_file(dir / "dam_break_1500.hdf5");
  ParticleData d = read_particles(dir / "dam_break_1500.hdf5", {{"all"}, {}});
  ASSERT_EQ(d.size(), 5u);
  EXPECT_TRUE(d.chosen.empty());
  EXPECT_DOUBLE_EQ(d.positions[2][2], 0.3);
  EXPECT_DOUBLE_EQ(d.positions[4][0], -2);
  EXPECT_EQ(d.time, 0.75);
  EXPECT_EQ(d.step, 1500);
  EXPECT_TRUE(d.radii.empty());
  ASSERT_NE(d.attribute("rho"), nullptr);
  EXPECT_EQ(d.attribute("rho")->values, (std::vector<float>{1000, 1001, 1002, 1000, 1001}));
  EXPECT_NE(d.attribute("m"), nullptr);
  EXPECT_EQ(d.attribute("p"), nullptr);   // only the fluid has it
  EXPECT_EQ(d.attribute("au"), nullptr);  // not stored
  const Attribute* vel = d.attribute("velocity");
  ASSERT_NE(vel, nullptr);
  EXPECT_EQ(vel->components, 3);
  EXPECT_EQ(std::vector<float>(vel->values.begin(), vel->values.begin() + 6),
            (std::vector<float>{1, 2, -1, 2, 2, -1}));
}

TEST(PySphParticles, SelectsArraysByName) {
  test::TempFolder dir;
  write_pysph_file(dir / "out.hdf5");
  ParticleData fluid = read_particles(dir / "out.hdf5", {{"fluid"}, {}});
  ASSERT_EQ(fluid.size(), 3u);
  EXPECT_NE(fluid.attribute("p"), nullptr);
  std::string e = error_of(dir / "out.hdf5", {{"water"}, {}});
  EXPECT_NE(e.find("no particle array \"water\" (the file has: fluid, solid)"), std::string::npos)
      << e;
  std::ofstream(dir / "fake.h5") << "not hdf5";
  EXPECT_NE(error_of(dir / "fake.h5").find("not an HDF5 file"), std::string::npos);
}

// A missing file is not "not an HDF5 file", and a dump cut short (a solver killed while
// writing) is not merely "cannot open": each says which file and what is wrong with it.
TEST(PySphParticles, MissingAndTruncatedFilesSaySo) {
  test::TempFolder dir;
  EXPECT_EQ(error_of(dir / "missing.hdf5"),
            "cannot read particles from " + (dir / "missing.hdf5").string() + ": no such file");
  write_pysph_file(dir / "whole.hdf5");
  const auto size = std::filesystem::file_size(dir / "whole.hdf5");
  std::filesystem::copy_file(dir / "whole.hdf5", dir / "cut.hdf5");
  std::filesystem::resize_file(dir / "cut.hdf5", size / 2);
  const std::string e = error_of(dir / "cut.hdf5");
  EXPECT_EQ(e.rfind("cannot read particles from " + (dir / "cut.hdf5").string() +
                        ": the HDF5 file is truncated or corrupt (",
                    0),
            0u)
      << e;
  EXPECT_NE(e.find("truncated file"), std::string::npos) << e;  // HDF5's own reason
}

TEST(PySphParticles, WithoutNamesTheFluidIsReadAndTheSpacingComesFromMassAndDensity) {
  test::TempFolder dir;
  write_pysph_file(dir / "named.hdf5");  // arrays fluid and solid, both moving
  const ParticleData named = read_particles(dir / "named.hdf5");
  EXPECT_EQ(named.size(), 3u);
  // The solid moves: not scenery (an inlet's fluid would too).
  EXPECT_EQ(named.chosen,
            "PySPH arrays fluid (named like a fluid); left out: solid (--arrays picks)");
  EXPECT_TRUE(named.scenery.empty());
  // m = 0.001, rho = 1000..1002: (m / rho)^(1/3) about 0.01 (the median particle has 1001).
  ASSERT_TRUE(named.spacing.has_value());
  EXPECT_NEAR(*named.spacing, std::cbrt(0.001 / 1001), 1e-12);

  hid_t f = H5Fcreate((dir / "moving.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t particles = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_array(particles, "tank", {{0, 0, 0}, {1, 0, 0}}, true, {}, /*still=*/true);
  write_array(particles, "water", {{0.5, 0.5, 0.5}}, true, {});
  H5Gclose(particles);
  H5Fclose(f);
  const ParticleData moving = read_particles(dir / "moving.h5");
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_DOUBLE_EQ(moving.positions[0][0], 0.5);
  // The tank stands still: the scenery, unless told otherwise.
  EXPECT_EQ(moving.chosen,
            "PySPH arrays water (their particles move, the others' do not); scenery: tank "
            "(--scenery picks)");
  ASSERT_EQ(moving.scenery.size(), 2u);
  EXPECT_DOUBLE_EQ(moving.scenery[1][0], 1.0);
  EXPECT_TRUE(read_particles(dir / "moving.h5", {{}, {"none"}}).scenery.empty());

  f = H5Fcreate((dir / "one.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  particles = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_array(particles, "fluid", {{0.5, 0.5, 0.5}}, true, {});
  H5Gclose(particles);
  H5Fclose(f);
  EXPECT_EQ(read_particles(dir / "one.h5").chosen, "PySPH arrays fluid (the file's only array)");
  EXPECT_EQ(read_particles(dir / "moving.h5", {{"water"}, {"tank"}}).scenery.size(), 2u);
  EXPECT_NE(error_of(dir / "moving.h5", {{"water"}, {"wall"}})
                .find("no particle array \"wall\" for the scenery (the file has: tank, water)"),
            std::string::npos);
  EXPECT_NE(error_of(dir / "moving.h5", {{"water"}, {"water"}})
                .find("particle array \"water\" is read as the fluid and as scenery"),
            std::string::npos);
  EXPECT_NE(error_of(dir / "p.csv", {{}, {"tank"}}).find("scenery arrays were named (tank)"),
            std::string::npos);
  EXPECT_EQ(read_particles(dir / "moving.h5", {{"all"}, {}}).size(), 3u);
}

TEST(PySphParticles, TwoDimensionalRunsGetZeroZ) {
  test::TempFolder dir;
  hid_t f = H5Fcreate((dir / "2d.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t particles = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_array(particles, "fluid", {{1, 2, 99}, {3, 4, 99}}, false, {});
  H5Gclose(particles);
  H5Fclose(f);
  ParticleData d = read_particles(dir / "2d.h5");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d.positions[1][1], 4);
  EXPECT_DOUBLE_EQ(d.positions[1][2], 0);
  EXPECT_FALSE(d.time.has_value());
  EXPECT_EQ(d.attribute("velocity")->values[5], 0.f);
  EXPECT_NE(d.chosen.find("no z stored: read as a 2D run in the x-y plane (z = 0)"),
            std::string::npos)
      << d.chosen;
}

// As PySPH writes a 2D run (trivial_inlet_outlet): z stored, all 0, the mass an area's; and
// an array with no particles yet, its stored properties empty.
TEST(PySphParticles, TwoDimensionalRunsWithZStoredAndAnEmptyFluid) {
  test::TempFolder dir;
  hid_t f = H5Fcreate((dir / "inlet.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t particles = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_array(particles, "fluid", {}, true, {});
  write_array(particles, "inlet", {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}}, true, {"p"});
  H5Gclose(particles);
  H5Fclose(f);
  const ParticleData fluid = read_particles(dir / "inlet.h5");
  EXPECT_EQ(fluid.size(), 0u);
  EXPECT_EQ(fluid.chosen,
            "PySPH arrays fluid (named like a fluid); left out: inlet (--arrays picks)");
  const ParticleData all = read_particles(dir / "inlet.h5", {{"all"}, {}});
  ASSERT_EQ(all.size(), 3u);
  EXPECT_NE(all.attribute("p"), nullptr);  // the empty array has no say
  ASSERT_TRUE(all.spacing.has_value());
  EXPECT_NEAR(*all.spacing, std::sqrt(0.001 / 1001), 1e-12);
}

// ---- GADGET-format snapshots ----

// A dataset of `rows` x `columns` values as `type` stores them (float, double, integers).
void write_rows(hid_t group, const char* name, hid_t type, std::size_t rows, int columns,
                const std::vector<double>& values) {
  const hsize_t dims[2] = {rows, hsize_t(columns)};
  hid_t space = H5Screate_simple(columns == 1 ? 1 : 2, dims, nullptr);
  hid_t set = H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(set);
  H5Sclose(space);
}

void write_header_attribute(hid_t header, const char* name, hid_t type,
                            const std::vector<double>& values) {
  const hsize_t n = values.size();
  hid_t space = H5Screate_simple(1, &n, nullptr);
  hid_t a = H5Acreate2(header, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, values.data());
  H5Aclose(a);
  H5Sclose(space);
}

// As SWIFT writes a snapshot: the header's scalars as arrays of one, the gas with float
// coordinates, Masses, Densities, SmoothingLengths, 64-bit ids and a tensor; dark matter
// (positions only) and stars whose mass is the table's.
void write_swift_file(const std::filesystem::path& path) {
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t header = H5Gcreate2(f, "Header", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_header_attribute(header, "Time", H5T_IEEE_F64LE, {0.125});
  write_header_attribute(header, "NumPart_ThisFile", H5T_STD_U32LE, {3, 2, 0, 0, 2, 0});
  write_header_attribute(header, "MassTable", H5T_IEEE_F64LE, {0, 0, 0, 0, 0.25, 0});
  write_header_attribute(header, "NumFilesPerSnapshot", H5T_STD_I32LE, {1});
  H5Gclose(header);
  hid_t gas = H5Gcreate2(f, "PartType0", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_rows(gas, "Coordinates", H5T_IEEE_F32LE, 3, 3, {0, 0, 0, 0.5, 0, 0, 0.25, 0.5, 1});
  write_rows(gas, "Velocities", H5T_IEEE_F32LE, 3, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9});
  write_rows(gas, "Masses", H5T_IEEE_F64LE, 3, 1, {8e-3, 8e-3, 8e-3});
  write_rows(gas, "Densities", H5T_IEEE_F64LE, 3, 1, {1, 1, 2});
  write_rows(gas, "SmoothingLengths", H5T_IEEE_F32LE, 3, 1, {0.25, 0.25, 0.5});
  write_rows(gas, "ParticleIDs", H5T_STD_U64LE, 3, 1, {10, 11, 12});
  write_rows(gas, "Tensor", H5T_IEEE_F64LE, 3, 9, std::vector<double>(27, 1.0));
  H5Gclose(gas);
  hid_t dark = H5Gcreate2(f, "PartType1", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_rows(dark, "Coordinates", H5T_IEEE_F64LE, 2, 3, {5, 5, 5, 6, 6, 6});
  H5Gclose(dark);
  hid_t stars = H5Gcreate2(f, "PartType4", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_rows(stars, "Coordinates", H5T_IEEE_F64LE, 2, 3, {1, 1, 1, 2, 2, 2});
  write_rows(stars, "Velocities", H5T_IEEE_F32LE, 2, 3, {0, 0, 0, 0, 0, 0});
  H5Gclose(stars);
  H5Fclose(f);
}

TEST(GadgetParticles, TheGasWithItsFieldsTimeAndSpacing) {
  test::TempFolder dir;
  write_swift_file(dir / "snap_0007.hdf5");
  const ParticleData d = read_particles(dir / "snap_0007.hdf5");
  ASSERT_EQ(d.size(), 3u);
  EXPECT_DOUBLE_EQ(d.positions[2][0], 0.25);
  EXPECT_DOUBLE_EQ(d.positions[2][2], 1);
  ASSERT_TRUE(d.time.has_value());
  EXPECT_DOUBLE_EQ(*d.time, 0.125);
  EXPECT_EQ(d.step, 7);  // the header holds none: the number ending the name
  ASSERT_NE(d.attribute("Velocities"), nullptr);
  EXPECT_EQ(d.attribute("Velocities")->components, 3);
  EXPECT_EQ(d.attribute("Velocities")->values[5], 6.f);
  EXPECT_EQ(d.attribute("SmoothingLengths")->values[2], 0.5f);
  EXPECT_EQ(d.attribute("ParticleIDs")->values[1], 11.f);
  EXPECT_EQ(d.attribute("Tensor"), nullptr);  // nine values per particle: not drawn
  ASSERT_TRUE(d.spacing.has_value());
  EXPECT_NEAR(*d.spacing, 0.2, 1e-12);  // the median (m / rho)^(1/3) of 8e-3 / {1, 1, 2}
  EXPECT_EQ(d.chosen, "GADGET-format PartType0 (the gas; --arrays picks)");
}

TEST(GadgetParticles, OtherTypesByNameWithTheMassTable) {
  test::TempFolder dir;
  write_swift_file(dir / "snap.h5");
  const ParticleData stars = read_particles(dir / "snap.h5", {{"PartType4"}, {}});
  ASSERT_EQ(stars.size(), 2u);
  ASSERT_NE(stars.attribute("Masses"), nullptr);
  EXPECT_EQ(stars.attribute("Masses")->values[1], 0.25f);
  EXPECT_FALSE(stars.spacing.has_value());  // no densities
  const ParticleData all = read_particles(dir / "snap.h5", {{"all"}, {}});
  EXPECT_EQ(all.size(), 7u);
  EXPECT_TRUE(all.attributes.empty());  // dark matter has nothing but positions
  EXPECT_EQ(all.chosen, "GADGET-format PartType0, PartType1, PartType4");
}

TEST(GadgetParticles, MissingTypesAndOtherLayoutsSaySo) {
  test::TempFolder dir;
  write_swift_file(dir / "snap.hdf5");
  EXPECT_EQ(error_of(dir / "snap.hdf5", {{"PartType2"}, {}}),
            (dir / "snap.hdf5").string() +
                ": no particle type \"PartType2\" (the file has: PartType0, PartType1, PartType4)");
  EXPECT_NE(
      error_of(dir / "snap.hdf5", {{}, {"PartType1"}}).find("a GADGET-format snapshot has no"),
      std::string::npos);
  hid_t f = H5Fcreate((dir / "dark.hdf5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Gclose(H5Gcreate2(f, "Header", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  hid_t dark = H5Gcreate2(f, "PartType1", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_rows(dark, "Coordinates", H5T_IEEE_F64LE, 1, 3, {5, 5, 5});
  H5Gclose(dark);
  H5Fclose(f);
  EXPECT_EQ(error_of(dir / "dark.hdf5"),
            (dir / "dark.hdf5").string() +
                ": no gas particles (PartType0), the SPH particles; the file has PartType1 "
                "(--arrays picks)");
  f = H5Fcreate((dir / "header.hdf5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Gclose(H5Gcreate2(f, "Header", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Fclose(f);
  EXPECT_EQ(
      error_of(dir / "header.hdf5", {{"all"}, {}}),
      (dir / "header.hdf5").string() + ": no particle types (no /PartType0 to /PartType5 group)");
  f = H5Fcreate((dir / "other.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Gclose(H5Gcreate2(f, "grid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Fclose(f);
  EXPECT_EQ(error_of(dir / "other.h5"),
            "cannot read particles from " + (dir / "other.h5").string() +
                ": neither PySPH's layout (/particles) nor a GADGET-format snapshot (/Header, "
                "/PartType0...); the file has /grid");
}

}  // namespace
}  // namespace voxspan
