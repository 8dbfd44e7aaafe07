// Calls from a solver into the library run with floating-point traps held.
#pragma once

#include <cfenv>

namespace voxspan {

// A solver may trap floating-point exceptions (gfortran's -ffpe-trap, feenableexcept). The
// library's arithmetic keeps to IEEE's non-stop results (1/0 = inf in a ray's slab test, a NaN
// sorted out afterwards), and Mesa's llvmpipe raises them in its start-up and its shaders: a trap
// there kills the solver. So each call in holds them, and restores the solver's traps and flags on
// the way out (the flags the library raised are not the solver's). Threads started inside (the
// writer, the driver's, TBB's) inherit the held environment.
class FloatingPointTrapsHeld {
 public:
  FloatingPointTrapsHeld() noexcept { std::feholdexcept(&solvers_); }
  ~FloatingPointTrapsHeld() { std::fesetenv(&solvers_); }
  FloatingPointTrapsHeld(const FloatingPointTrapsHeld&) = delete;
  FloatingPointTrapsHeld& operator=(const FloatingPointTrapsHeld&) = delete;

 private:
  std::fenv_t solvers_;
};

}  // namespace voxspan
