#include "insitu/outputs/output.h"

#include <cstdio>

namespace voxspan {

std::string step_file_name(std::string_view prefix, std::int64_t step, std::string_view extension) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "_%08lld.", static_cast<long long>(step));
  std::string name(prefix);
  name.append(digits).append(extension);
  return name;
}

}  // namespace voxspan
