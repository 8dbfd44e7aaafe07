// insitu/runtime/particle_reductions.h - the reductions the triggers' conditions name
// (insitu/config/condition.h), over a step's owned particles and every rank's: one parallel
// pass (oneTBB) over the particles for all the reductions wanted, then two all-reduces in an
// MPI job (the minima with the negated maxima, then the sums with the counts), so that every
// rank has the same values. Nothing is allocated per step.
//
// What a reduction of nothing is (no particle, none in the box, every value NaN): count 0,
// sum 0, min +inf, max -inf (their identities), mean NaN, which makes every comparison with
// it false. A NaN value is left out of its attribute's reductions (a particle with a NaN
// pressure has no pressure, and still counts in count()); a NaN position is in no box. Ghosts
// are left out: each particle counts once over the ranks.
//
// Cost: one read of each attribute named per owned particle, a square root for a vector's
// length, six compares per box, in blocks that stay in cache (docs/benchmarks.md, "Triggers on
// conditions").
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "insitu/config/condition.h"
#include "voxspan/particles.h"

namespace voxspan {

class Communicator;

class ParticleReductions {
 public:
  // The attribute-and-box pairs one pass reduces at most (a condition's reductions of one
  // attribute over one box share a pair).
  static constexpr std::size_t kMaxPairs = 32;

  // Throws voxspan::Error when the reductions take more than kMaxPairs pairs or name a box
  // `boxes` lacks. `comm`: the job's, or null in one process.
  ParticleReductions(std::span<const Reduction> reductions,
                     const std::map<std::string, ConditionBox>& boxes, Communicator* comm);

  // Computes the reductions whose `wanted` is set (one per reduction). Under MPI every rank
  // calls it with the same `wanted`. Allocates nothing.
  void run(const ParticleView& particles, std::span<const char> wanted);

  // Reduction i's value from the latest run (NaN when it was not wanted, or its attribute
  // is missing on some rank).
  double value(std::size_t i) const { return values_[i]; }
  // Whether some rank's solver passed no attribute of reduction i's name at the latest run.
  bool missing(std::size_t i) const { return missing_[pair_of_[i]]; }

 private:
  struct Pair {
    std::string attribute;  // empty: count(); "x", "y", "z": the positions' axes
    int axis = -1;          // 0, 1, 2 for x, y, z
    int box = -1;           // into boxes_; -1: every particle
  };
  std::size_t pair_index(const Reduction& r);

  std::vector<Reduction> reductions_;
  std::vector<std::size_t> pair_of_;  // per reduction
  std::vector<Pair> pairs_;
  std::vector<ConditionBox> boxes_;  // those the reductions name: at most one a pair
  Communicator* comm_;
  std::vector<double> values_;
  std::array<bool, kMaxPairs> missing_{};
};

}  // namespace voxspan
