#include "render/volume_merge.h"

#include <limits>

#include "render/stat_names.h"

namespace voxspan {

VolumeMerge::VolumeMerge(const Camera& camera, const VolumeOptions& options, bool deep)
    : options_(options),
      frame_(camera),
      lattice_(volume_lattice(frame_.tan_half_y, frame_.height, options)),
      host_(options),
      deep_(deep) {}

void VolumeMerge::extend_run(Ray& m, std::int32_t first, std::int32_t last, std::int64_t previous) {
  if (!deep_) return;
  if (m.run_end == m.run_begin || first != previous + 1) {
    end_run(m);
    Run& r = runs_.emplace_back();
    r.first = first;
    r.color_before = m.ray.color;
    r.transmittance_before = m.ray.transmittance;
    ++m.run_end;
  }
  runs_.back().last = last;
}

void VolumeMerge::end_run(Ray& m) {
  if (!deep_ || m.run_end == m.run_begin) return;
  Run& r = runs_.back();
  r.color = (m.ray.color - r.color_before) / r.transmittance_before;
  r.transmittance = m.ray.transmittance / r.transmittance_before;
}

void VolumeMerge::note_hits(Ray& m, int before) {
  const int added = m.hits.count + m.hits.unlit_count - before;
  if (added <= 0) return;
  for (int h = std::min(before, model::kMaxIsoHits); h < m.hits.count; ++h)
    m.hit_run[std::size_t(h)] = m.run_end - m.run_begin - 1;
  counts_.iso_hits += added;
  if (m.first_depth == 0 && m.hits.count > 0) {
    m.first_depth = m.hits.hit[0].depth * m.scale;
    m.first_is_hit = true;
  }
}

// One shared sample, as the caster composites one (VolumeCaster's TileMarch::composite).
void VolumeMerge::composite(Ray& m, std::int32_t index, double s, double w) {
  const bool defined = w > 0 && (!options_.shepard || w >= options_.weight_floor);
  const double q = !defined ? 0.0 : options_.shepard ? s / w : s;
  counts_.samples += defined ? 1 : 0;
  const double z = lattice_.depth(index);
  const float length = float(lattice_.extent(z) * m.scale);
  const float before = m.ray.transmittance;
  const int hits = m.hits.count + m.hits.unlit_count;
  m.ray = host_.vx_sample(m.ray, float(q), defined ? 1u : 0u, float(z), length);
  note_hits(m, hits);
  if (m.first_depth == 0 && before >= 0.5f && m.ray.transmittance < 0.5f)
    m.first_depth = float(z * m.scale);
}

// One rank's segment behind what the ray holds: the crossings at the join, then its light.
void VolumeMerge::join(Ray& m, const PartSegment& seg) {
  const int hits = m.hits.count + m.hits.unlit_count;
  const uint first_defined = (seg.flags & PartSegment::kFirstDefined) != 0 ? 1u : 0u;
  m.ray =
      host_.vx_iso_crossings(m.ray, seg.q_first, first_defined, float(lattice_.depth(seg.first)));
  note_hits(m, hits);
  if (m.first_depth == 0) {
    // Its first hit, or where the whole ray's opacity reaches 0.5 in it: the segment's own point
    // of 0.5 (exact when nothing absorbs in front of it), else its end.
    float half = 0;
    if (m.ray.transmittance >= 0.5f && m.ray.transmittance * seg.transmittance < 0.5f)
      half = seg.half_depth > 0 ? seg.half_depth : float(lattice_.depth(seg.last) * m.scale);
    const float hit = seg.hit_depth;
    m.first_depth = hit > 0 && (half == 0 || hit < half) ? hit : half;
  }
  m.ray.color += m.ray.transmittance * seg.color;
  m.ray.transmittance *= seg.transmittance;
  m.ray.q = seg.q_last;
  m.ray.depth = float(lattice_.depth(seg.last));
  m.ray.defined = (seg.flags & PartSegment::kLastDefined) != 0 ? 1u : 0u;
}

void VolumeMerge::merge(std::uint32_t pixel, std::span<const std::span<const RawSample>> raws,
                        std::span<const std::span<const PartSegment>> segments,
                        std::vector<HitQuery>& queries) {
  Ray& m = rays_.emplace_back();
  m.pixel = pixel;
  const int x = int(pixel % std::uint32_t(frame_.width)),
            y = int(pixel / std::uint32_t(frame_.width));
  m.ray = host_.vx_ray_start();
  m.scale = float(glm::length(frame_.view_ray(x, y)));
  m.run_begin = m.run_end = std::uint32_t(runs_.size());
  host_.record_into(&m.hits);
  const std::size_t ranks = raws.size();
  std::vector<std::size_t>& next_raw = next_raw_;
  std::vector<std::size_t>& next_segment = next_segment_;
  next_raw.assign(ranks, 0);
  next_segment.assign(ranks, 0);
  constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();
  std::int64_t previous = std::numeric_limits<std::int64_t>::min();
  for (;;) {
    // The nearest item left: a shared sample (whose sums every rank adds) or a segment.
    std::int64_t raw_at = kNone, segment_at = kNone;
    std::size_t segment_rank = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      if (next_raw[r] < raws[r].size())
        raw_at = std::min<std::int64_t>(raw_at, raws[r][next_raw[r]].index);
      if (next_segment[r] < segments[r].size() && segments[r][next_segment[r]].first < segment_at) {
        segment_at = segments[r][next_segment[r]].first;
        segment_rank = r;
      }
    }
    if (raw_at == kNone && segment_at == kNone) break;
    bool stopped = false;
    if (raw_at < segment_at) {
      double s = 0, w = 0;
      for (std::size_t r = 0; r < ranks; ++r)
        if (next_raw[r] < raws[r].size() && raws[r][next_raw[r]].index == raw_at) {
          s += raws[r][next_raw[r]].s;
          w += raws[r][next_raw[r]].w;
          ++next_raw[r];
        }
      if (raw_at != previous + 1) m.ray.defined = 0u;
      extend_run(m, std::int32_t(raw_at), std::int32_t(raw_at), previous);
      composite(m, std::int32_t(raw_at), s, w);
      previous = raw_at;
    } else {
      const PartSegment& seg = segments[segment_rank][next_segment[segment_rank]++];
      if (seg.first != previous + 1) m.ray.defined = 0u;
      extend_run(m, seg.first, seg.last, previous);
      join(m, seg);
      previous = seg.last;
      stopped = (seg.flags & PartSegment::kStopped) != 0;
    }
    if (stopped || m.ray.transmittance < options_.termination) {
      ++counts_.rays_stopped;
      break;
    }
  }
  end_run(m);
  m.first_query = std::uint32_t(queries.size());
  for (int h = 0; h < m.hits.count; ++h)
    queries.push_back({pixel, m.hits.hit[std::size_t(h)].depth});
}

void VolumeMerge::finish(std::span<const FieldSums> sums, std::vector<glm::vec4>& colors,
                         std::vector<float>& depths, std::vector<std::uint32_t>* deep_counts,
                         std::vector<DeepSample>* deep) {
  colors.resize(rays_.size());
  depths.resize(rays_.size());
  for (std::size_t k = 0; k < rays_.size(); ++k) {
    Ray& m = rays_[k];
    const int x = int(m.pixel % std::uint32_t(frame_.width)),
              y = int(m.pixel / std::uint32_t(frame_.width));
    const glm::dvec3 dir = frame_.view_ray(x, y);
    for (int h = 0; h < m.hits.count; ++h) {
      model::IsoHit& hit = m.hits.hit[std::size_t(h)];
      const FieldSums& f = sums[m.first_query + std::size_t(h)];
      host_.refine_hit(hit, f, dir, options_.shepard, lattice_.k * double(hit.depth));
      const model::vec3 light =
          host_.hit_light(hit, field_gradient(f, options_.shepard), frame_, x, y);
      m.ray.color += light;
      if (deep_) {
        Run& r = runs_[m.run_begin + m.hit_run[std::size_t(h)]];
        r.color += light / r.transmittance_before;
      }
    }
    if (m.first_is_hit) m.first_depth = m.hits.hit[0].depth * m.scale;
    colors[k] = options_.backdrop != nullptr
                    ? over_backdrop(*options_.backdrop, x, y, m.ray.color + m.hits.unlit,
                                    m.ray.transmittance, options_.background)
                    : host_.pixel_color(m.ray, m.hits.unlit, options_.background, frame_, x, y);
    depths[k] = m.first_depth;
    counts_.iso_hits_unlit += m.hits.unlit_count;
    if (deep_ && deep != nullptr && deep_counts != nullptr) {
      if (m.run_end > m.run_begin) {  // the hits past the lit ones: the last run's
        Run& last = runs_[m.run_end - 1];
        last.color += m.hits.unlit / last.transmittance_before;
      }
      deep_counts->push_back(m.run_end - m.run_begin);
      for (std::uint32_t run = m.run_begin; run < m.run_end; ++run) {
        const Run& r = runs_[run];
        const double front = lattice_.depth(r.first), back = lattice_.depth(r.last);
        deep->push_back({float((front - 0.5 * lattice_.extent(front)) * m.scale),
                         float((back + 0.5 * lattice_.extent(back)) * m.scale),
                         glm::vec4(r.color, 1.0f - r.transmittance)});
      }
    }
  }
  rays_.clear();
  runs_.clear();
}

void ParallelVolumeMerge::finish(std::span<const FieldSums> sums, std::vector<glm::vec4>& colors,
                                 std::vector<float>& depths,
                                 std::vector<std::uint32_t>* deep_counts,
                                 std::vector<DeepSample>* deep) {
  struct Out {
    std::vector<glm::vec4> colors;
    std::vector<float> depths;
    std::vector<std::uint32_t> deep_counts;
    std::vector<DeepSample> deep;
  };
  std::vector<Out> out(chunks_.size());
  tbb::parallel_for(std::size_t(0), chunks_.size(), [&](std::size_t c) {
    Out& o = out[c];
    chunks_[c]->finish(sums.subspan(query_start_[c], query_start_[c + 1] - query_start_[c]),
                       o.colors, o.depths, &o.deep_counts, &o.deep);
  });
  colors.clear();
  depths.clear();
  for (const Out& o : out) {
    colors.insert(colors.end(), o.colors.begin(), o.colors.end());
    depths.insert(depths.end(), o.depths.begin(), o.depths.end());
    if (deep_counts != nullptr)
      deep_counts->insert(deep_counts->end(), o.deep_counts.begin(), o.deep_counts.end());
    if (deep != nullptr) deep->insert(deep->end(), o.deep.begin(), o.deep.end());
  }
}

VolumeCounts ParallelVolumeMerge::counts() const {
  VolumeCounts total;
  for (const auto& c : chunks_) total += c->counts();
  return total;
}

VolumeCounts render_with_deep(VolumeRenderer& renderer, const Camera& camera,
                              std::span<const VolumeParticle> particles,
                              const VolumeOptions& options, Recorder& recorder, VolumeFrame& out) {
  std::vector<SampleRange> hulls;
  VolumeCounts counts = renderer.cover(camera, particles, options, recorder, hulls);
  const std::size_t pixels = std::size_t(camera.width) * std::size_t(camera.height);
  PixelRanges none;
  none.start.assign(pixels + 1, 0);
  VolumePart part;
  counts += renderer.render_part(none, recorder, part);
  ParallelVolumeMerge merge(camera, options, true);
  std::vector<FieldSums> sums;
  std::vector<glm::vec4> colors;
  std::vector<std::uint32_t> deep_counts;
  {
    auto t = recorder.host(pass::volume);
    merge.merge(0, pixels, 1, [&](std::size_t p, auto& raws, auto& segments) {
      raws[0] = part.raws_of(p);
      segments[0] = part.segments_of(p);
    });
  }
  renderer.field_sums(merge.queries(), recorder, sums);
  auto t = recorder.host(pass::volume);
  out.reset(camera.width, camera.height);
  DeepImage& deep = out.deep;
  deep.width = camera.width;
  deep.height = camera.height;
  deep.samples.clear();
  merge.finish(sums, colors, out.depth, &deep_counts, &deep.samples);
  deep.start.assign(pixels + 1, 0);
  for (std::size_t p = 0; p < pixels; ++p) {
    deep.start[p + 1] = deep.start[p] + deep_counts[p];
    out.picture.set(int(p % std::size_t(camera.width)), int(p / std::size_t(camera.width)),
                    colors[p]);
  }
  counts += merge.counts();
  record(counts, recorder);
  return counts;
}

}  // namespace voxspan
