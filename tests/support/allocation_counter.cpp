#include "tests/support/allocation_counter.h"

#include <execinfo.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

// GCC takes the free() in a replaced operator delete for a mismatch; here malloc is what
// operator new returns.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> g_allocations{0};
thread_local long t_allocations = 0;
}  // namespace

// Every form that a non-replaced default would pair with another allocator is replaced, so
// that each block is freed by the allocator that made it (AddressSanitizer checks: a nothrow
// new left to the runtime and freed here is an alloc-dealloc mismatch).
namespace {
thread_local int t_traces_left = 0;
thread_local bool t_tracing = false;

// Where the calling thread allocated, to stderr (backtrace() itself may allocate once).
void trace(std::size_t size) noexcept {
  if (t_tracing) return;
  t_tracing = true;
  --t_traces_left;
  std::fprintf(stderr, "allocation of %zu bytes on the traced thread, from:\n", size);
  void* frames[32];
  backtrace_symbols_fd(frames, backtrace(frames, 32), STDERR_FILENO);
  t_tracing = false;
}

void* counted_malloc(std::size_t size) noexcept {
  ++g_allocations;
  ++t_allocations;
  if (t_traces_left > 0) trace(size);
  return std::malloc(size ? size : 1);
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace voxspan::test {
long allocations() { return g_allocations.load(); }
long thread_allocations() { return t_allocations; }
void trace_thread_allocations(int most) { t_traces_left = most; }
}  // namespace voxspan::test
