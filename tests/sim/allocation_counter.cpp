#include "allocation_counter.h"

#include <atomic>
#include <cstdlib>
#include <new>

// GCC takes the free() in a replaced operator delete for a mismatch; here malloc is what
// operator new returns.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> g_allocations{0};
thread_local long t_allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  ++t_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace voxspan::test {
long allocations() { return g_allocations.load(); }
long thread_allocations() { return t_allocations; }
}  // namespace voxspan::test
