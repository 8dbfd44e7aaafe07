// voxspan/error.h - the one exception type the library throws at its own boundaries
// (construction, configuration). The per-step entry points never throw into the solver:
// they return a status and log instead.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace voxspan {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Builds the message from parts: throw make_error("tile budget ", mb, " MiB is too small").
template <class... Parts> Error make_error(const Parts&... parts) {
  std::ostringstream s;
  (s << ... << parts);
  return Error(s.str());
}

}  // namespace voxspan
