// Slabs along x over MPI: the histogram cuts, the all-to-all exchange that carries both
// migrating particles and ghosts, and the global reductions of the driver.
#include "decomposition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace dambreak {
namespace {

using Packed = Decomposition::Packed;

// Bins of the x histogram: far more than ranks, so that a cut falls within a small fraction
// of a particle spacing of where it should.
constexpr std::size_t kBins = 4096;
constexpr double kInf = std::numeric_limits<double>::infinity();

Packed pack(const Fluid& f, std::size_t i) {
  return {f.x[i], f.y[i], f.z[i], f.vx[i], f.vy[i], f.vz[i], f.rho[i], f.id[i]};
}

void store(Fluid& f, std::size_t i, const Packed& p) {
  f.x[i] = p.x, f.y[i] = p.y, f.z[i] = p.z;
  f.vx[i] = p.vx, f.vy[i] = p.vy, f.vz[i] = p.vz;
  f.rho[i] = p.rho, f.id[i] = p.id;
}

// Keeps, in their order, the particles i for which keep(i) is true; keep(i) sees particle i
// before anything overwrites it.
template <class Keep> void keep_if(Fluid& f, Keep keep) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!keep(i)) continue;
    if (kept != i) store(f, kept, pack(f, i));
    ++kept;
  }
  f.resize(kept);
}

// The particles' x over all ranks, counted in kBins bins from the least x to the greatest.
struct Histogram {
  double lo = 0, bin_width = 0;
  std::vector<std::uint64_t> counts;  // empty: no particle anywhere
};

// Collective. Only finite positions count: the solver's diagnostics catch the others, and
// migration gives them to the last rank.
Histogram global_histogram(const Fluid& fluid, MPI_Comm comm) {
  double least[2] = {kInf, kInf};  // the least x, and the least -x
  for (const float x : fluid.x) {
    if (!std::isfinite(x)) continue;
    least[0] = std::min(least[0], double(x));
    least[1] = std::min(least[1], -double(x));
  }
  MPI_Allreduce(MPI_IN_PLACE, least, 2, MPI_DOUBLE, MPI_MIN, comm);
  Histogram h;
  h.lo = least[0];
  const double hi = -least[1];
  if (!(h.lo <= hi)) return h;
  h.bin_width = (hi - h.lo) / double(kBins);
  h.counts.assign(kBins, 0);
  for (const float x : fluid.x) {
    if (!std::isfinite(x)) continue;
    const double u = h.bin_width > 0 ? (double(x) - h.lo) / h.bin_width : 0;
    ++h.counts[std::min(std::size_t(u), kBins - 1)];
  }
  MPI_Allreduce(MPI_IN_PLACE, h.counts.data(), int(kBins), MPI_UINT64_T, MPI_SUM, comm);
  return h;
}

}  // namespace

Decomposition::Decomposition(MPI_Comm comm, long rebalance_every)
    : comm_(comm), rebalance_every_(rebalance_every) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  // Until the first cut rank 0 owns all space.
  bounds_.assign(std::size_t(size_) + 1, kInf);
  bounds_.front() = -kInf;
  MPI_Type_contiguous(int(sizeof(Packed)), MPI_BYTE, &packed_type_);
  MPI_Type_commit(&packed_type_);
  outgoing_.resize(std::size_t(size_));
  for (auto* v : {&send_counts_, &send_offsets_, &receive_counts_, &receive_offsets_})
    v->resize(std::size_t(size_));
}

Decomposition::~Decomposition() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Type_free(&packed_type_);
}

void Decomposition::set_bounds(std::vector<double> bounds) {
  if (bounds.size() != std::size_t(size_) + 1 || !std::is_sorted(bounds.begin(), bounds.end()))
    throw std::invalid_argument("slab bounds: one more than ranks, in increasing order");
  bounds_ = std::move(bounds);
  bounds_.front() = -kInf;
  bounds_.back() = kInf;
}

int Decomposition::owner_of(double x) const {
  // The bounds between the slabs that lie at or left of x (a NaN counts as right of all).
  return int(std::upper_bound(bounds_.begin() + 1, bounds_.end() - 1, x) - (bounds_.begin() + 1));
}

void Decomposition::distribute(Fluid& fluid) {
  // Every rank built the same fluid: each keeps every size()-th particle, so that the
  // histogram counts each particle once, and the migration below takes it to its slab.
  const auto ranks = std::uint32_t(size_), me = std::uint32_t(rank_);
  keep_if(fluid, [&](std::size_t i) { return fluid.id[i] % ranks == me; });
  rebalance(fluid);
  route(fluid);
}

void Decomposition::migrate(Fluid& fluid) {
  if (rebalance_every_ > 0 && ++steps_ % rebalance_every_ == 0) rebalance(fluid);
  route(fluid);
}

void Decomposition::route(Fluid& fluid) {
  keep_if(fluid, [&](std::size_t i) {
    const int owner = owner_of(fluid.x[i]);
    if (owner != rank_) outgoing_[std::size_t(owner)].push_back(pack(fluid, i));
    return owner == rank_;
  });
  append(fluid, exchange());
}

void Decomposition::append_ghosts(Fluid& fluid, float width) {
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    // The slabs that come within `width` of the particle are a run of consecutive ranks.
    const double x = fluid.x[i];
    const int first = owner_of(x - width), last = owner_of(x + width);
    for (int r = first; r <= last; ++r)
      if (r != rank_) outgoing_[std::size_t(r)].push_back(pack(fluid, i));
  }
  append(fluid, exchange());
}

void Decomposition::max_over_ranks(std::span<float> values) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_FLOAT, MPI_MAX, comm_);
}

void Decomposition::rebalance(const Fluid& fluid) {
  const Histogram h = global_histogram(fluid, comm_);
  if (h.counts.empty()) return;  // no fluid anywhere: keep the slabs
  // Cut r at the bin edge nearest to r / size of the particles. Every rank computes the same
  // bounds from the same sums, which is all that ownership needs; the balance is as good as
  // the bins (particles of one x all go to one rank).
  std::uint64_t total = 0;
  for (const std::uint64_t n : h.counts) total += n;
  std::size_t bin = 0;
  std::uint64_t below = 0;  // particles in bins [0, bin)
  for (int r = 1; r < size_; ++r) {
    const double target = double(total) * r / size_;
    while (bin < kBins && double(below + h.counts[bin]) <= target) below += h.counts[bin++];
    const bool after =
        bin < kBins && double(below + h.counts[bin]) - target < target - double(below);
    bounds_[std::size_t(r)] = h.lo + double(bin + (after ? 1 : 0)) * h.bin_width;
  }
}

const std::vector<Packed>& Decomposition::exchange() {
  send_.clear();
  for (std::size_t r = 0; r < outgoing_.size(); ++r) {
    send_counts_[r] = int(outgoing_[r].size());
    send_offsets_[r] = int(send_.size());
    send_.insert(send_.end(), outgoing_[r].begin(), outgoing_[r].end());
    outgoing_[r].clear();
  }
  MPI_Alltoall(send_counts_.data(), 1, MPI_INT, receive_counts_.data(), 1, MPI_INT, comm_);
  int received = 0;
  for (std::size_t r = 0; r < receive_counts_.size(); ++r) {
    receive_offsets_[r] = received;
    received += receive_counts_[r];
  }
  received_.resize(std::size_t(received));
  MPI_Alltoallv(send_.data(), send_counts_.data(), send_offsets_.data(), packed_type_,
                received_.data(), receive_counts_.data(), receive_offsets_.data(), packed_type_,
                comm_);
  return received_;
}

void Decomposition::append(Fluid& fluid, const std::vector<Packed>& incoming) const {
  const std::size_t first = fluid.size();
  fluid.resize(first + incoming.size());
  for (std::size_t k = 0; k < incoming.size(); ++k) store(fluid, first + k, incoming[k]);
}

Diagnostics combine_over_ranks(const Diagnostics& local, MPI_Comm comm) {
  std::uint64_t counts[3] = {local.fluid, local.nonfinite, local.outside};
  double maxima[3] = {local.front, local.max_density_error, local.max_speed};
  double error_sum = local.mean_density_error * double(local.fluid);
  MPI_Allreduce(MPI_IN_PLACE, counts, 3, MPI_UINT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, maxima, 3, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &error_sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  Diagnostics d;
  d.fluid = counts[0];
  d.nonfinite = counts[1];
  d.outside = counts[2];
  d.front = maxima[0];
  d.max_density_error = maxima[1];
  d.max_speed = maxima[2];
  d.mean_density_error = d.fluid ? error_sum / double(d.fluid) : 0;
  return d;
}

std::uint64_t sum_over_ranks(std::uint64_t count, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_UINT64_T, MPI_SUM, comm);
  return count;
}

bool ids_complete(const Fluid& fluid, std::size_t owned, std::size_t count, MPI_Comm comm) {
  // How often each id is owned, summed over the ranks; the last entry counts ids out of range.
  std::vector<int> seen(count + 1, 0);
  for (std::size_t i = 0; i < owned; ++i) ++seen[std::min(std::size_t(fluid.id[i]), count)];
  MPI_Allreduce(MPI_IN_PLACE, seen.data(), int(seen.size()), MPI_INT, MPI_SUM, comm);
  return seen.back() == 0 &&
         std::all_of(seen.begin(), seen.end() - 1, [](int n) { return n == 1; });
}

}  // namespace dambreak
