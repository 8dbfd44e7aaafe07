#include "insitu/runtime/host_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace voxspan {

HostMemory host_memory() {
  HostMemory m;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    unsigned long long size = 0, resident = 0;
    if (std::fscanf(f, "%llu %llu", &size, &resident) == 2)
      m.rss_bytes = resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
    std::fclose(f);
  }
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) == 0)
    m.peak_bytes = static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux: KiB
  // The kernel updates the high-water mark lazily: it read below the resident size on 21 of
  // 23 stats lines. The peak is at least what is resident now, and never falls between reads.
  static std::atomic<std::uint64_t> seen{0};
  std::uint64_t peak = std::max(m.peak_bytes, m.rss_bytes), before = seen.load();
  while (before < peak && !seen.compare_exchange_weak(before, peak)) {}
  m.peak_bytes = std::max(peak, before);
  return m;
}

}  // namespace voxspan
