// decomposition.h - the dam break as an MPI job: the fluid cut into slabs along the flow
// direction x, one per rank; a rank owns the particles whose x lies in its slab and keeps the
// others' particles near it as ghosts (sph.h, Domain).
//
// The slab bounds are cut at the quantiles of a global histogram of x (one all-reduce), so
// that every rank owns as many particles as the others: at the start, and again every
// `rebalance_every` steps. Cuts made once at the start would not stay balanced: the column
// collapses into a surge that runs the length of the tank, and the slab of the right-most
// rank, which starts at the column's right edge, would take in all of it. Between two
// re-balances the fluid moves about a smoothing length, so the counts drift little.
//
// Each step, after the drift, the particles whose x left the slab go to the rank that now owns
// them (migrate), and every rank receives as ghosts the particles of the others within the
// ghost width of its slab (append_ghosts). Both go through one all-to-all exchange, so a
// particle reaches its owner however many slabs away it lies (after a re-balance, or where
// slabs are narrower than the ghost width); a job of many ranks would talk to its neighbours
// only. A rank may own nothing (more ranks than the fluid has columns): it still takes part.
// Wall particles are fixed and every rank keeps all of them (the solver finds the ones near
// its fluid through its wall grid), so they are never exchanged.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sph.h"

namespace dambreak {

class Decomposition final : public Domain {
 public:
  // rebalance_every: steps between two re-balances; 0 keeps the slabs cut at the start.
  explicit Decomposition(MPI_Comm comm, long rebalance_every = 50);
  ~Decomposition() override;
  Decomposition(const Decomposition&) = delete;
  Decomposition& operator=(const Decomposition&) = delete;

  void distribute(Fluid& fluid) override;
  void migrate(Fluid& fluid) override;
  void append_ghosts(Fluid& fluid, float width) override;
  void max_over_ranks(std::span<float> values) override;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank r's slab is [bounds()[r], bounds()[r + 1]): size() + 1 values, from -inf to +inf.
  const std::vector<double>& bounds() const { return bounds_; }
  // Cuts the slabs at these bounds (the same on every rank) until the next re-balance.
  void set_bounds(std::vector<double> bounds);
  // The rank whose slab holds x.
  int owner_of(double x) const;

  // The state of one particle as it travels between ranks.
  struct Packed {
    float x, y, z, vx, vy, vz, rho;
    std::uint32_t id;
  };

 private:
  void rebalance(const Fluid& fluid);
  // Sends every particle whose x lies in another rank's slab to that rank; appends arrivals.
  void route(Fluid& fluid);
  // Sends outgoing_[r] to rank r; returns what every rank sent here, by rank.
  const std::vector<Packed>& exchange();
  void append(Fluid& fluid, const std::vector<Packed>& incoming) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  long rebalance_every_ = 0, steps_ = 0;
  std::vector<double> bounds_;
  MPI_Datatype packed_type_ = MPI_DATATYPE_NULL;
  std::vector<std::vector<Packed>> outgoing_;  // by destination rank
  std::vector<Packed> send_, received_;
  std::vector<int> send_counts_, send_offsets_, receive_counts_, receive_offsets_;
};

// The diagnostics of the whole fluid from every rank's own (collective): counts summed, the
// front, density errors and speed the maxima, the mean density error over all particles.
Diagnostics combine_over_ranks(const Diagnostics& local, MPI_Comm comm);

// The sum over the ranks of `count` (collective).
std::uint64_t sum_over_ranks(std::uint64_t count, MPI_Comm comm);

// Whether the ranks' owned particles together carry the ids 0 .. count - 1, each exactly once
// (collective; the same answer on every rank).
bool ids_complete(const Fluid& fluid, std::size_t owned, std::size_t count, MPI_Comm comm);

}  // namespace dambreak
