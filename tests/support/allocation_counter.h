// Counts allocations through operator new, replaced in allocation_counter.cpp: a test binary
// that compiles that file sees every allocation of the process (the shared library's too),
// in total and per thread (tests only).
#pragma once

namespace voxspan::test {

long allocations();         // all threads
long thread_allocations();  // the calling thread
// The calling thread's next `most` allocations print their backtraces to stderr (0: none).
void trace_thread_allocations(int most);

}  // namespace voxspan::test
