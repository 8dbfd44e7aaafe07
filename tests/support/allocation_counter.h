// Counts allocations through operator new, replaced in allocation_counter.cpp: a test binary
// that compiles that file sees every allocation of the process (the shared library's too),
// in total and per thread (tests only).
#pragma once

namespace voxspan::test {

long allocations();         // all threads
long thread_allocations();  // the calling thread

}  // namespace voxspan::test
