// render/gl/passes/thread_index.glsl - one thread per item over more items than one dispatch
// dimension holds (65535 groups): the pass dispatches a 2D grid (render/gl/passes/dispatch.h) and
// each thread reads its item number here; threads past u_thread_count do nothing.
uniform uint u_thread_count;

uint thread_index() {
  return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
}
