#include "insitu/runtime/particle_reductions.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "insitu/parallel/communicator.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Particles per task: large enough that a task's overhead is lost in its reads, and fixed, so
// that the sums are the same from run to run (parallel_deterministic_reduce).
constexpr std::size_t kGrain = 16384;

struct Sums {
  double min = kInf, max = -kInf, sum = 0, count = 0;
};
using Partial = std::array<Sums, ParticleReductions::kMaxPairs>;

// A pair bound to this step's arrays.
struct Bound {
  const AttributeView* attribute = nullptr;  // null with an axis or for count()
  int axis = -1;
  int box = -1;
};

// Particles per block of a task: the positions, the box masks and one pair's values of a
// block stay in the core's cache while each pair is reduced over it in a tight loop.
constexpr std::size_t kBlock = 512;

// values[0..n) = the scalars of particles begin..begin+n, as doubles; a loop per type and
// layout, so that the dense ones (the usual) vectorize.
void read(const StridedScalars& s, std::size_t begin, std::size_t n, double* values) {
  const char* p = static_cast<const char*>(s.data) + begin * s.stride;
  if (s.type == ScalarType::float32) {
    if (s.stride == sizeof(float))
      for (std::size_t i = 0; i < n; ++i) values[i] = reinterpret_cast<const float*>(p)[i];
    else
      for (std::size_t i = 0; i < n; ++i)
        values[i] = *reinterpret_cast<const float*>(p + i * s.stride);
  } else if (s.stride == sizeof(double)) {
    for (std::size_t i = 0; i < n; ++i) values[i] = reinterpret_cast<const double*>(p)[i];
  } else {
    for (std::size_t i = 0; i < n; ++i)
      values[i] = *reinterpret_cast<const double*>(p + i * s.stride);
  }
}

// values = |a| of a 3-vector attribute, using `scratch`.
void read_length(const AttributeView& a, std::size_t begin, std::size_t n, double* values,
                 double* scratch) {
  read(a.component[0], begin, n, values);
  for (std::size_t i = 0; i < n; ++i) values[i] *= values[i];
  for (std::size_t c = 1; c < 3; ++c) {
    read(a.component[c], begin, n, scratch);
    for (std::size_t i = 0; i < n; ++i) values[i] += scratch[i] * scratch[i];
  }
  for (std::size_t i = 0; i < n; ++i) values[i] = std::sqrt(values[i]);
}

// The values not NaN (and inside, with a mask) into s. Without branches: a box that holds
// half the particles at random would mispredict every other one.
void accumulate(const double* values, const std::uint8_t* inside, std::size_t n, Sums& s) {
  double lo = s.min, hi = s.max, sum = s.sum, count = s.count;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = values[i];
    const bool take = !std::isnan(v) && (inside == nullptr || inside[i] != 0);
    lo = take && v < lo ? v : lo;
    hi = take && v > hi ? v : hi;
    sum += take ? v : 0.0;
    count += take ? 1.0 : 0.0;
  }
  s = {lo, hi, sum, count};
}

// The pass of one range of particles over the active pairs, a block at a time.
struct Pass {
  std::span<const StridedScalars, 3> axes;
  std::span<const std::size_t> active;  // pair indices
  std::span<const Bound> bound;         // per pair
  std::span<const ConditionBox> boxes;
  std::span<const char> box_used;  // per box: some active pair is over it
  bool positions;                  // some active pair reads them

  void operator()(std::size_t begin, std::size_t end, Partial& acc) const {
    std::array<std::array<double, kBlock>, 3> p;
    std::array<double, kBlock> values, scratch;
    std::array<std::array<std::uint8_t, kBlock>, ParticleReductions::kMaxPairs> inside;
    for (std::size_t b = begin; b < end; b += kBlock) {
      const std::size_t n = std::min(kBlock, end - b);
      if (positions)
        for (std::size_t a = 0; a < 3; ++a) read(axes[a], b, n, p[a].data());
      for (std::size_t k = 0; k < boxes.size(); ++k)
        if (box_used[k]) mask(boxes[k], p, n, inside[k].data());
      for (std::size_t k : active) {
        const Bound& pair = bound[k];
        const double* v = values.data();
        if (pair.axis >= 0) v = p[std::size_t(pair.axis)].data();
        else if (pair.attribute == nullptr) std::fill_n(values.data(), n, 1.0);
        else if (pair.attribute->components == 1)
          read(pair.attribute->component[0], b, n, values.data());
        else read_length(*pair.attribute, b, n, values.data(), scratch.data());
        accumulate(v, pair.box >= 0 ? inside[std::size_t(pair.box)].data() : nullptr, n, acc[k]);
      }
    }
  }

  // NaN is in no box.
  static void mask(const ConditionBox& box, const std::array<std::array<double, kBlock>, 3>& p,
                   std::size_t n, std::uint8_t* inside) {
    for (std::size_t i = 0; i < n; ++i)
      inside[i] = p[0][i] >= box.lo[0] && p[0][i] <= box.hi[0] && p[1][i] >= box.lo[1] &&
                  p[1][i] <= box.hi[1] && p[2][i] >= box.lo[2] && p[2][i] <= box.hi[2];
  }
};

void join(Partial& a, const Partial& b, std::span<const std::size_t> active) {
  for (std::size_t k : active) {
    a[k].min = std::min(a[k].min, b[k].min);
    a[k].max = std::max(a[k].max, b[k].max);
    a[k].sum += b[k].sum;
    a[k].count += b[k].count;
  }
}

}  // namespace

ParticleReductions::ParticleReductions(std::span<const Reduction> reductions,
                                       const std::map<std::string, ConditionBox>& boxes,
                                       Communicator* comm)
    : reductions_(reductions.begin(), reductions.end()),
      comm_(comm),
      values_(reductions.size(), kNaN) {
  std::vector<std::string> box_names;  // of boxes_: the boxes the reductions name
  for (const Reduction& r : reductions_) {
    std::size_t index = pair_index(r);
    if (index == pairs_.size()) {
      if (pairs_.size() == kMaxPairs)
        throw make_error("the triggers' conditions reduce more than ", kMaxPairs,
                         " attributes and boxes (", r.text(), " is one too many)");
      Pair pair{r.attribute, -1, -1};
      if (r.attribute.size() == 1 && r.attribute[0] >= 'x' && r.attribute[0] <= 'z')
        pair.axis = r.attribute[0] - 'x';
      if (!r.box.empty()) {
        const auto given = boxes.find(r.box);
        if (given == boxes.end()) throw make_error(r.text(), ": no box \"", r.box, "\"");
        const auto at = std::find(box_names.begin(), box_names.end(), r.box);
        pair.box = int(at - box_names.begin());
        if (at == box_names.end()) {
          box_names.push_back(r.box);
          boxes_.push_back(given->second);
        }
      }
      pairs_.push_back(std::move(pair));
    }
    pair_of_.push_back(index);
  }
}

std::size_t ParticleReductions::pair_index(const Reduction& r) {
  for (std::size_t k = 0; k < pair_of_.size(); ++k)
    if (reductions_[k].attribute == r.attribute && reductions_[k].box == r.box) return pair_of_[k];
  return pairs_.size();
}

void ParticleReductions::run(const ParticleView& particles, std::span<const char> wanted) {
  std::array<bool, kMaxPairs> on{};
  for (std::size_t i = 0; i < reductions_.size(); ++i)
    if (wanted[i]) on[pair_of_[i]] = true;
  std::array<Bound, kMaxPairs> bound{};
  std::array<std::size_t, kMaxPairs> active{};
  std::array<double, kMaxPairs> absent{};  // 1 where this rank lacks the attribute
  std::array<char, kMaxPairs> box_used{};
  std::size_t active_count = 0;
  bool positions = false;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    if (!on[k]) continue;
    const Pair& pair = pairs_[k];
    Bound& b = bound[k];
    b.axis = pair.axis;
    b.box = pair.box;
    if (pair.axis < 0 && !pair.attribute.empty()) {
      b.attribute = particles.find_attribute(pair.attribute);
      if (b.attribute == nullptr) {
        absent[k] = 1;
        continue;
      }
    }
    positions = positions || b.axis >= 0 || b.box >= 0;
    if (b.box >= 0) box_used[std::size_t(b.box)] = 1;
    active[active_count++] = k;
  }

  const std::span<const std::size_t> live(active.data(), active_count);
  const std::array<StridedScalars, 3> axes = {particles.axis(0), particles.axis(1),
                                              particles.axis(2)};
  const Pass pass{axes, live, bound, boxes_, std::span(box_used.data(), boxes_.size()), positions};
  Partial total = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, particles.owned_count(), kGrain), Partial{},
      [&](const tbb::blocked_range<std::size_t>& r, Partial acc) {
        pass(r.begin(), r.end(), acc);
        return acc;
      },
      [&](Partial a, const Partial& b) {
        join(a, b, live);
        return a;
      });

  const std::size_t n = pairs_.size();
  if (comm_ != nullptr && comm_->size() > 1) {
    std::array<double, 2 * kMaxPairs> lows{};
    std::array<double, 3 * kMaxPairs> sums{};
    for (std::size_t k = 0; k < n; ++k) {
      lows[2 * k] = total[k].min;
      lows[2 * k + 1] = -total[k].max;
      sums[3 * k] = total[k].sum;
      sums[3 * k + 1] = total[k].count;
      sums[3 * k + 2] = absent[k];
    }
    comm_->min(std::span(lows.data(), 2 * n));
    comm_->sum(std::span(sums.data(), 3 * n));
    for (std::size_t k = 0; k < n; ++k) {
      total[k] = {lows[2 * k], -lows[2 * k + 1], sums[3 * k], sums[3 * k + 1]};
      absent[k] = sums[3 * k + 2];
    }
  }

  for (std::size_t k = 0; k < n; ++k) missing_[k] = absent[k] > 0;
  for (std::size_t i = 0; i < reductions_.size(); ++i) {
    const std::size_t k = pair_of_[i];
    const Sums& s = total[k];
    double& v = values_[i];
    if (!wanted[i] || missing_[k]) {
      v = kNaN;
      continue;
    }
    switch (reductions_[i].op) {
      case ReductionOp::min: v = s.min; break;
      case ReductionOp::max: v = s.max; break;
      case ReductionOp::sum: v = s.sum; break;
      case ReductionOp::mean: v = s.count > 0 ? s.sum / s.count : kNaN; break;
      case ReductionOp::count: v = s.count; break;
    }
  }
}

}  // namespace voxspan
