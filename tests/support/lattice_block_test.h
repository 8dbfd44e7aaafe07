// A gtest fixture: a 24^3 lattice block of touching spheres (spacing dx, radius dx/2, the
// runtime's `auto`), the interior left out as the classifier leaves it (tools/scenes/lattice.h),
// and a temporary folder: the level-set outputs' tests (tests only).
#pragma once

#include <gtest/gtest.h>

#include "tests/support/temp_folder.h"
#include "tools/scenes/lattice.h"

namespace voxspan::test {

class LatticeBlockTest : public ::testing::Test {
 protected:
  static constexpr int kSide = 24;
  static constexpr double kDx = 0.01;
  LatticeScene scene = make_lattice_block(kSide, kDx, float(kDx / 2));
  TempFolder dir;
};

}  // namespace voxspan::test
