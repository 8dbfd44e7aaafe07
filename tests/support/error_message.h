// The message of the voxspan::Error a call throws, for the tests of error messages (tests
// only).
#pragma once

#include <string>

#include "voxspan/error.h"

namespace voxspan::test {

// The message of the Error that `call()` throws; "" when it throws none.
template <class Call> std::string error_message(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace voxspan::test
