// The C API from C (c_api_client.c) and from C++ (layouts, NULL handles, errors).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "c_api_client.h"
#include "voxspan/voxspan.h"

namespace {

// An adapter with defaults but the particle spacing, logging nothing (NULL on error).
voxspan_adapter* quiet_adapter(double spacing) {
  voxspan_set_log_level(0);
  voxspan_adapter_options o;
  voxspan_adapter_options_init(&o);
  o.particle_spacing = spacing;
  return voxspan_adapter_create(&o);
}

TEST(CApi, CClientClassifiesALattice) {
  c_api_client_result r{};
  ASSERT_EQ(c_api_client_run(&r), 0);
  EXPECT_EQ(r.status, VOXSPAN_OK);
  EXPECT_EQ(r.cells_full, 8);  // 2x2x2 full cells, all touching the air outside
  EXPECT_EQ(r.boundary, 64);
  EXPECT_EQ(r.returned, 64);
  EXPECT_EQ(r.first_radius, 1.0f);
  EXPECT_EQ(r.bad_index_status, VOXSPAN_INVALID_INPUT);
  EXPECT_NE(std::string(r.bad_index_message).find("index type 17"), std::string::npos);
}

TEST(CApi, SceneryIsCopiedKeptWithoutNaNsAndOutlivesAddAttribute) {
  voxspan_adapter* a = quiet_adapter(0.5);
  ASSERT_NE(a, nullptr);
  std::vector<float> xyz = {0, 0, 0, 1, 0, 0, NAN, 0, 0, 2, 0, 0};
  voxspan_particles* walls = voxspan_particles_create();
  ASSERT_EQ(voxspan_particles_set_aos(walls, VOXSPAN_FLOAT32, xyz.data(), 4, 0), VOXSPAN_OK);
  ASSERT_EQ(voxspan_particles_set_radius(walls, 0.25), VOXSPAN_OK);
  size_t kept = 0;
  ASSERT_EQ(voxspan_adapter_set_scenery(a, walls, &kept), VOXSPAN_OK) << voxspan_last_error();
  EXPECT_EQ(kept, 3u);
  xyz.assign(xyz.size(), 9.0f);  // copied: the solver's arrays may change
  ASSERT_EQ(voxspan_adapter_add_attribute(a, "velocity"), VOXSPAN_OK);
  const float* xyzr = nullptr;
  ASSERT_EQ(voxspan_adapter_scenery(a, &xyzr), 3u);
  EXPECT_EQ(std::vector<float>(xyzr, xyzr + 12),
            (std::vector<float>{0, 0, 0, 0.25f, 1, 0, 0, 0.25f, 2, 0, 0, 0.25f}));
  EXPECT_EQ(voxspan_adapter_set_scenery(a, nullptr, nullptr), VOXSPAN_INVALID_INPUT);
  EXPECT_NE(std::string(voxspan_last_error()).find("scenery"), std::string::npos)
      << voxspan_last_error();
  EXPECT_EQ(voxspan_adapter_set_scenery(nullptr, walls, nullptr), VOXSPAN_INVALID_INPUT);
  voxspan_particles_destroy(walls);
  voxspan_adapter_destroy(a);
}

TEST(CApi, SoaDoubleOneBasedCellIndexAndAttributes) {
  voxspan_adapter* a = quiet_adapter(1.0);
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(voxspan_adapter_add_attribute(a, "velocity"), VOXSPAN_OK);
  std::vector<double> x, y, z, v;
  std::vector<std::int32_t> cell;
  for (int i = 0; i < 10; ++i) {
    x.push_back(0.5 + i), y.push_back(0.5), z.push_back(0.5);
    v.insert(v.end(), {double(i), 0, 0});
    cell.push_back(i / 2 + 1);  // 1-based
  }
  voxspan_particles* p = voxspan_particles_create();
  voxspan_grid* g = voxspan_grid_create();
  ASSERT_EQ(voxspan_particles_set_soa(p, VOXSPAN_FLOAT64, x.data(), y.data(), z.data(), 10),
            VOXSPAN_OK);
  ASSERT_EQ(voxspan_particles_set_radius(p, 0.6), VOXSPAN_OK);
  ASSERT_EQ(voxspan_particles_set_vector(p, "velocity", VOXSPAN_FLOAT64, v.data(), 0), VOXSPAN_OK);
  const double origin[3] = {0, 0, 0};
  const int dims[3] = {5, 1, 1};
  ASSERT_EQ(voxspan_grid_set_cell_index(g, origin, 2.0, dims, VOXSPAN_INT32, cell.data()),
            VOXSPAN_OK);
  ASSERT_EQ(voxspan_grid_set_index_base(g, 1), VOXSPAN_OK);
  ASSERT_EQ(voxspan_adapter_execute(a, 0, 0.0, p, g), VOXSPAN_OK) << voxspan_last_error();

  voxspan_step_stats s;
  ASSERT_EQ(voxspan_adapter_stats(a, &s), VOXSPAN_OK);
  EXPECT_EQ(s.boundary, 10u);
  EXPECT_EQ(s.cells_partial, 5u);
  EXPECT_EQ(s.grid_built, 1);
  const float* values = nullptr;
  int components = 0;
  ASSERT_EQ(voxspan_adapter_attribute(a, "velocity", &values, &components), 30u);
  EXPECT_EQ(components, 3);
  EXPECT_EQ(values[3 * 9], 9.0f);
  const float* spheres = nullptr;
  ASSERT_EQ(voxspan_adapter_boundary(a, &spheres), 10u);
  EXPECT_FLOAT_EQ(spheres[3], 0.6f);
  double o2[3];
  double cs = 0;
  int d2[3];
  const std::uint8_t* states = nullptr;
  EXPECT_EQ(voxspan_adapter_cell_states(a, o2, &cs, d2, &states), 5u);
  EXPECT_EQ(cs, 2.0);
  EXPECT_EQ(states[0], 1);  // partial

  // A cell index out of range fails the step with a message; the handles stay usable.
  cell[3] = 99;
  EXPECT_EQ(voxspan_adapter_execute(a, 1, 0.0, p, g), VOXSPAN_INVALID_INPUT);
  EXPECT_NE(std::string(voxspan_last_error()).find("particle 3 is 99"), std::string::npos)
      << voxspan_last_error();
  voxspan_grid_clear(g);
  EXPECT_EQ(voxspan_adapter_execute(a, 2, 0.0, p, g), VOXSPAN_OK);

  voxspan_grid_destroy(g);
  voxspan_particles_destroy(p);
  voxspan_adapter_destroy(a);
}

TEST(CApi, NullAndInvalidArgumentsAreErrors) {
  voxspan_set_log_level(0);
  EXPECT_EQ(voxspan_adapter_create(nullptr), nullptr);
  EXPECT_NE(std::string(voxspan_last_error()).find("options is NULL"), std::string::npos);
  voxspan_adapter_options o;
  voxspan_adapter_options_init(&o);
  EXPECT_EQ(voxspan_adapter_create(&o), nullptr);  // no spacing, no full count
  EXPECT_NE(std::string(voxspan_last_error()).find("particle_spacing"), std::string::npos);
  EXPECT_EQ(voxspan_adapter_execute(nullptr, 0, 0, nullptr, nullptr), VOXSPAN_INVALID_INPUT);
  voxspan_particles* p = voxspan_particles_create();
  EXPECT_EQ(voxspan_particles_set_aos(p, 5, nullptr, 0, 0), VOXSPAN_INVALID_INPUT);
  EXPECT_EQ(voxspan_particles_set_aos(p, VOXSPAN_FLOAT32, nullptr, 3, 0), VOXSPAN_INVALID_INPUT);
  // A stride shorter than one particle's values reads them overlapping: refused, named.
  const float xyz[9] = {};
  EXPECT_EQ(voxspan_particles_set_aos(p, VOXSPAN_FLOAT32, xyz, 3, 4), VOXSPAN_INVALID_INPUT);
  EXPECT_NE(std::string(voxspan_last_error())
                .find("positions: a stride of 4 bytes is less than one particle's x, y, z "
                      "(12 bytes)"),
            std::string::npos)
      << voxspan_last_error();
  EXPECT_EQ(voxspan_particles_set_vector(p, "v", VOXSPAN_FLOAT64, xyz, 16), VOXSPAN_INVALID_INPUT);
  EXPECT_EQ(voxspan_particles_set_aos(p, VOXSPAN_FLOAT32, xyz, 3, 12), VOXSPAN_OK);
  voxspan_particles_destroy(p);
  voxspan_grid* g = voxspan_grid_create();
  const double origin[3] = {0, 0, 0};
  const int dims[3] = {0, 1, 1};
  unsigned offsets[2] = {0, 0};
  EXPECT_EQ(voxspan_grid_set_offsets(g, origin, 1.0, dims, VOXSPAN_UINT32, offsets),
            VOXSPAN_INVALID_INPUT);
  voxspan_grid_destroy(g);
  voxspan_set_log_level(1);
}

}  // namespace
