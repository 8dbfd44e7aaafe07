#include "insitu/runtime/host_memory.h"

#include <sys/resource.h>
#include <unistd.h>

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
  return m;
}

}  // namespace voxspan
