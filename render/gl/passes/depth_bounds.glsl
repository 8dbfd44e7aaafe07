// render/gl/passes/depth_bounds.glsl - per 16x16-pixel screen block, the depth range that the
// spheres touching it cover, gathered by the binning pass and read by the compress pass so that
// it scans only the chunks of a column that can hold fluid (most of the grid is empty depth).
// Exact: voxels outside the range are never set. Inner-full cells lie between boundary
// particles along every ray (they are surrounded by full cells whose particles are voxelized),
// except where the near plane cuts them: compress checks the cell at the near plane.
// Large spheres (render/gl/passes/sphere_work.glsl) would touch too many blocks: their range goes
// to one extra entry after the blocks, which holds for every pixel.
// Storage: uvec2 per block, zero when no sphere touches it; x = ~bits(nearest depth) and
// y = bits(farthest depth), both kept with atomicMax (positive floats order like their bits).

const int kDepthBlock = 16;

uniform int u_depth_blocks_x;     // blocks across the image
uniform int u_depth_block_count;  // blocks in the image; the large spheres' entry follows

int depth_block(ivec2 pixel) {
  return pixel.x / kDepthBlock + (pixel.y / kDepthBlock) * u_depth_blocks_x;
}

uvec2 depth_bounds_bits(float nearest, float farthest) {
  return uvec2(~floatBitsToUint(nearest), floatBitsToUint(farthest));
}
