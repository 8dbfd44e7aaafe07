// OpenVDB snapshots read back with OpenVDB's own reader: the level set holds the whole fluid
// although only the boundary particles were given, attributes and cell states are there.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetMeasure.h>

#include <iostream>

#include "insitu/io/vdb_inspect.h"
#include "insitu/outputs/formats/vdb_snapshot.h"
#include "tests/support/lattice_block_test.h"
#include "tests/support/temp_folder.h"
#include "tools/scenes/lattice.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

openvdb::GridPtrVecPtr read_grids(const std::filesystem::path& path) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  return grids;
}

template <class GridT>
typename GridT::Ptr grid_named(const openvdb::GridPtrVec& grids, const std::string& name) {
  for (const auto& g : grids)
    if (g->getName() == name) return openvdb::gridPtrCast<GridT>(g);
  return nullptr;
}

// A 24^3 block of touching spheres (radius dx/2): its particle volume is (24 dx)^3.
class VdbSnapshot : public test::LatticeBlockTest {
 protected:
  double particle_volume() const { return std::pow(kSide * kDx, 3); }
};

TEST_F(VdbSnapshot, LevelSetHoldsTheWholeFluidFromItsBoundaryParticles) {
  // The scene really leaves the interior out: most cells inside are inner-full.
  ASSERT_GT(scene.count_state(cell::kInnerFull), 500u);
  ASSERT_LT(scene.boundary.size(), scene.all.size() / 2);

  std::vector<float> pressure(scene.boundary.size()), velocity(3 * scene.boundary.size());
  for (std::size_t i = 0; i < scene.boundary.size(); ++i) {
    pressure[i] = scene.boundary[i].z * 1000.f;
    velocity[3 * i] = 1, velocity[3 * i + 2] = scene.boundary[i].x;
  }
  std::vector<AttributeSpan> attributes = {{"pressure", 1, pressure}, {"velocity", 3, velocity}};
  VdbSnapshotInput input{scene.boundary, scene.cells(), attributes, 40, 0.125};
  VdbSnapshotReport report = write_vdb_snapshot(dir / "snap.vdb", input, VdbSnapshotSettings{});
  EXPECT_FLOAT_EQ(float(report.voxel_size), float(kDx / 2));  // the radius
  EXPECT_FLOAT_EQ(float(report.closing), float(kDx / 2));
  EXPECT_EQ(report.particles, scene.boundary.size());
  EXPECT_EQ(report.inner_full_cells, scene.count_state(cell::kInnerFull));
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);

  openvdb::GridPtrVecPtr grids = read_grids(dir / "snap.vdb");
  auto fluid = grid_named<openvdb::FloatGrid>(*grids, "fluid");
  ASSERT_TRUE(fluid);
  EXPECT_EQ(fluid->getGridClass(), openvdb::GRID_LEVEL_SET);
  double volume = openvdb::tools::levelSetVolume(*fluid);
  EXPECT_NEAR(volume / particle_volume(), 1.0, 0.10) << "volume " << volume;
  std::cout << "default voxel: volume / particle volume = " << volume / particle_volume() << "\n";

  // Inside at the centre (whose particles were left out), outside beyond the block.
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sdf(*fluid);
  const double mid = 0.5 * kSide * kDx;
  EXPECT_LT(sdf.wsSample(openvdb::Vec3R(mid, mid, mid)), 0);
  EXPECT_LT(sdf.wsSample(openvdb::Vec3R(mid, mid, 0.6 * kDx)), 0);
  EXPECT_GT(sdf.wsSample(openvdb::Vec3R(mid, mid, -0.3 * kDx)), 0);
  EXPECT_GT(sdf.wsSample(openvdb::Vec3R(mid, mid, kSide * kDx + 2 * kDx)), 0);
  // The surface stays where the spheres put it: dx/2 beyond the outer particles' centres, and
  // between four of them no deeper than the closed spheres' dimple (0.29 dx).
  const double on_particle = 11.5 * kDx;
  EXPECT_NEAR(sdf.wsSample(openvdb::Vec3R(on_particle, on_particle, 0.0)), 0.0, 0.15 * kDx);
  EXPECT_NEAR(sdf.wsSample(openvdb::Vec3R(mid, mid, 0.0)), 0.29 * kDx, 0.15 * kDx);

  auto p = grid_named<openvdb::FloatGrid>(*grids, "pressure");
  ASSERT_TRUE(p);
  float lo = 1e9f, hi = -1e9f;
  for (auto it = p->cbeginValueOn(); it; ++it) lo = std::min(lo, *it), hi = std::max(hi, *it);
  EXPECT_FLOAT_EQ(lo, scene.boundary.front().z * 1000.f);
  EXPECT_FLOAT_EQ(hi, scene.boundary.back().z * 1000.f);
  // On the surface, a voxel holds its closest particle's value: below the corner particle,
  // and a half spacing inside the top face.
  openvdb::Vec3d below_corner(0.5 * kDx, 0.5 * kDx, 0.0);
  openvdb::Vec3d under_top(on_particle, on_particle, kSide * kDx - 0.5 * kDx);
  auto pa = p->getConstAccessor();
  EXPECT_TRUE(pa.isValueOn(p->transform().worldToIndexCellCentered(below_corner)));
  EXPECT_FLOAT_EQ(pa.getValue(p->transform().worldToIndexCellCentered(below_corner)),
                  float(0.5 * kDx * 1000.0));
  EXPECT_NEAR(pa.getValue(p->transform().worldToIndexCellCentered(under_top)),
              (kSide - 0.5) * kDx * 1000.0, 1e-3);
  auto v = grid_named<openvdb::Vec3SGrid>(*grids, "velocity");
  ASSERT_TRUE(v);
  openvdb::Vec3s v_corner =
      v->getConstAccessor().getValue(v->transform().worldToIndexCellCentered(below_corner));
  EXPECT_EQ(v_corner, openvdb::Vec3s(1.f, 0.f, float(0.5 * kDx)));

  auto states = grid_named<openvdb::Int32Grid>(*grids, "cell_state");
  ASSERT_TRUE(states);
  EXPECT_DOUBLE_EQ(states->voxelSize()[0], scene.cell_size);
  std::size_t not_inner_empty = scene.states.size() - scene.count_state(cell::kInnerEmpty);
  EXPECT_EQ(states->activeVoxelCount(), not_inner_empty);
  auto acc = states->getConstAccessor();
  for (int k = 0; k < scene.dims[2]; ++k)
    for (int j = 0; j < scene.dims[1]; ++j)
      for (int i = 0; i < scene.dims[0]; ++i) {
        // World position of the cell centre maps back to the cell's voxel.
        openvdb::Vec3d centre(scene.origin[0] + (i + 0.5) * scene.cell_size,
                              scene.origin[1] + (j + 0.5) * scene.cell_size,
                              scene.origin[2] + (k + 0.5) * scene.cell_size);
        openvdb::Coord c = states->transform().worldToIndexCellCentered(centre);
        ASSERT_EQ(acc.getValue(c),
                  scene.states[std::size_t(i) +
                               std::size_t(scene.dims[0]) * (j + std::size_t(scene.dims[1]) * k)]);
      }
}

// Without the fill the file would hold only the skin: the test above would fail without it.
TEST_F(VdbSnapshot, WithoutTheFillOnlyTheSkinRemains) {
  VdbSnapshotSettings settings;
  settings.fill_inner = false;
  settings.cell_states = false;
  write_vdb_snapshot(dir / "skin.vdb", {scene.boundary, scene.cells(), {}, 0, 0}, settings);
  openvdb::GridPtrVecPtr grids = read_grids(dir / "skin.vdb");
  ASSERT_EQ(grids->size(), 1u);
  auto fluid = grid_named<openvdb::FloatGrid>(*grids, "fluid");
  double volume = openvdb::tools::levelSetVolume(*fluid);
  EXPECT_LT(volume / particle_volume(), 0.8) << volume;
}

TEST_F(VdbSnapshot, FinerVoxelsAndNoClosingKeepTheVolume) {
  for (double voxel : {kDx / 4, kDx / 3}) {
    VdbSnapshotSettings settings;
    settings.voxel_size = voxel;
    write_vdb_snapshot(dir / "fine.vdb", {scene.boundary, scene.cells(), {}, 0, 0}, settings);
    auto fluid = grid_named<openvdb::FloatGrid>(*read_grids(dir / "fine.vdb"), "fluid");
    double ratio = openvdb::tools::levelSetVolume(*fluid) / particle_volume();
    EXPECT_NEAR(ratio, 1.0, 0.10) << "voxel " << voxel;
    std::cout << "voxel " << voxel / kDx << " dx: volume / particle volume = " << ratio << "\n";
  }
  // Spheres a little larger than half the spacing close by themselves (no closing needed).
  test::LatticeScene big = test::make_lattice_block(kSide, kDx, float(0.62 * kDx));
  VdbSnapshotSettings settings;
  settings.closing = 0.0;
  settings.voxel_size = kDx / 4;
  write_vdb_snapshot(dir / "big.vdb", {big.boundary, big.cells(), {}, 0, 0}, settings);
  auto fluid = grid_named<openvdb::FloatGrid>(*read_grids(dir / "big.vdb"), "fluid");
  EXPECT_NEAR(openvdb::tools::levelSetVolume(*fluid) / particle_volume(), 1.0, 0.10);
}

TEST_F(VdbSnapshot, AllParticlesWithoutCellsGiveTheSameVolume) {
  write_vdb_snapshot(dir / "all.vdb", {scene.all, CellStatesView{}, {}, 0, 0},
                     VdbSnapshotSettings{});
  auto fluid = grid_named<openvdb::FloatGrid>(*read_grids(dir / "all.vdb"), "fluid");
  EXPECT_NEAR(openvdb::tools::levelSetVolume(*fluid) / particle_volume(), 1.0, 0.10);
}

TEST_F(VdbSnapshot, BadParticlesAreCountedAndEmptyInputStillWritesAFile) {
  std::vector<ParticleSphere> p = scene.boundary;
  p[0].x = std::nanf("");
  p[1].radius = 0;
  VdbSnapshotReport r = write_vdb_snapshot(dir / "bad.vdb", {p, scene.cells(), {}, 0, 0}, {});
  EXPECT_EQ(r.particles_invalid, 2u);
  EXPECT_EQ(r.particles, p.size() - 2);

  VdbSnapshotReport empty = write_vdb_snapshot(dir / "empty.vdb", {}, {});
  EXPECT_EQ(empty.level_set_voxels, 0u);
  VdbFileSummary summary = inspect_vdb(dir / "empty.vdb");
  ASSERT_EQ(summary.grids.size(), 1u);
  EXPECT_EQ(summary.grids[0].active_voxels, 0u);
}

TEST_F(VdbSnapshot, InspectorListsGridsAndRendersTheLevelSet) {
  std::vector<float> density(scene.boundary.size(), 1000.f);
  std::vector<AttributeSpan> attributes = {{"density", 1, density}};
  write_vdb_snapshot(dir / "i.vdb", {scene.boundary, scene.cells(), attributes, 7, 0.5}, {});
  VdbFileSummary s = inspect_vdb(dir / "i.vdb");
  ASSERT_EQ(s.grids.size(), 3u);
  auto named = [&](const std::string& name) -> const VdbGridSummary& {
    for (const VdbGridSummary& g : s.grids)
      if (g.name == name) return g;
    throw std::runtime_error("no grid " + name);
  };
  const VdbGridSummary& fluid = named("fluid");
  EXPECT_EQ(fluid.value_type, "float");
  EXPECT_EQ(fluid.grid_class, "Level Set");
  EXPECT_NEAR(fluid.level_set_volume / particle_volume(), 1.0, 0.10);
  EXPECT_NEAR(fluid.world_min[0], 0.0, 4 * kDx);  // the narrow band reaches a little outside
  EXPECT_DOUBLE_EQ(named("density").min_value, 1000);
  EXPECT_DOUBLE_EQ(named("density").max_value, 1000);
  EXPECT_EQ(named("cell_state").value_type, "int32");
  EXPECT_DOUBLE_EQ(named("cell_state").max_value, cell::kInnerFull);
  bool has_step = false;
  for (const auto& [key, value] : s.metadata) has_step |= key == "step" && value == "7";
  EXPECT_TRUE(has_step);

  LevelSetView view;
  view.width = 96;
  view.height = 64;
  ImageRGBA8 image = render_level_set(dir / "i.vdb", view);
  ASSERT_EQ(image.pixels.size(), 96u * 64 * 4);
  const std::uint8_t* corner = &image.pixels[0];
  const std::uint8_t* centre = &image.pixels[(32 * 96 + 48) * 4];
  EXPECT_NE(std::vector<int>(corner, corner + 3), std::vector<int>(centre, centre + 3))
      << "the block covers the centre of the picture";
  EXPECT_THROW(inspect_vdb(dir / "missing.vdb"), Error);
}

}  // namespace
}  // namespace voxspan
