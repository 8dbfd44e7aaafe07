#include "insitu/step_outputs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "insitu/png_image.h"
#include "insitu/vdb_snapshot.h"
#include "voxspan/log.h"

namespace voxspan {

struct StepOutputs::SnapshotSlot {
  std::vector<ParticleSphere> spheres;
  std::vector<NamedAttribute> attributes;
  CellStatesData cells;
  std::int64_t step = 0;
  double time = 0;

  std::vector<AttributeSpan> attribute_views() const {
    std::vector<AttributeSpan> views;
    for (const NamedAttribute& a : attributes) views.push_back(a.view());
    return views;
  }
};

struct StepOutputs::StatsSlot {
  std::string line;
};

namespace {

// "<prefix>_<step, 8 digits>.<extension>": sorts by step, and ffmpeg's glob input takes it.
std::string step_file_name(std::string_view prefix, std::int64_t step, const char* extension) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "_%08lld.", static_cast<long long>(step));
  std::string name(prefix);
  name.append(digits).append(extension);
  return name;
}

// The writer thread's time in one job, added to a counter when the scope ends.
class JobTimer {
 public:
  explicit JobTimer(std::atomic<std::int64_t>& total)
      : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~JobTimer() {
    total_ += std::chrono::duration_cast<std::chrono::microseconds>(
                  std::chrono::steady_clock::now() - start_).count();
  }
  JobTimer(const JobTimer&) = delete;
  JobTimer& operator=(const JobTimer&) = delete;

 private:
  std::atomic<std::int64_t>& total_;
  std::chrono::steady_clock::time_point start_;
};

// Slots per pool: the queue's jobs, one running, one being filled (insitu/slot_pool.h).
std::size_t pool_size(const Config& config) { return std::size_t(config.writer.queue_size) + 2; }

}  // namespace

StepOutputs::StepOutputs(const Config& config, std::vector<std::string> view_names,
                         double spacing)
    : config_(config), view_names_(std::move(view_names)),
      vdb_radius_(config.outputs.vdb.radius.value_or(spacing > 0 ? 0.5 * spacing : 0.0)),
      png_folder_(config.folder_of(config.outputs.png)),
      vdb_folder_(config.folder_of(config.outputs.vdb)),
      vtk_folder_(config.folder_of(config.outputs.vtk)),
      frames_(std::make_unique<SlotPool<FrameSlot>>(pool_size(config))),
      vdb_slots_(std::make_unique<SlotPool<SnapshotSlot>>(pool_size(config))),
      vtk_slots_(std::make_unique<SlotPool<SnapshotSlot>>(pool_size(config))),
      stats_slots_(std::make_unique<SlotPool<StatsSlot>>(pool_size(config))),
      writer_(config.writer) {
  if (config.outputs.stats.enabled)
    stats_log_ = std::make_unique<StatsLog>(config.folder_of(config.outputs.stats) /
                                            config.outputs.stats.file);
  if (config.outputs.vtk.enabled) {
    if (config.outputs.vtk.particles)
      particles_pvd_ = std::make_unique<PvdSeries>(vtk_folder_ / "particles.pvd", config.writer.fsync);
    if (config.outputs.vtk.cells)
      cells_pvd_ = std::make_unique<PvdSeries>(vtk_folder_ / "cells.pvd", config.writer.fsync);
  }
}

StepOutputs::~StepOutputs() {
  writer_.drain();
  if (stats_log_) {
    try {
      stats_log_->sync();
    } catch (const std::exception& e) {
      log_warning("stats file: ", e.what());
    }
  }
}

void StepOutputs::drain() { writer_.drain(); }

OutputCounts StepOutputs::counts() const {
  return {png_written_.load(), stats_written_.load(), vdb_written_.load(), vtk_written_.load(),
          1e-6 * double(writer_microseconds_.load())};
}

template <class Slot, std::unique_ptr<SlotPool<Slot>> StepOutputs::*Pool,
          void (StepOutputs::*Write)(Slot&)>
bool StepOutputs::submit(Slot* slot, const char* label) {
  // Two pointers fit std::function's small buffer: a job allocates nothing.
  const bool accepted = writer_.submit(label, [this, slot]() {
    SlotLease<Slot> lease(*(this->*Pool), slot);
    JobTimer timer(writer_microseconds_);
    (this->*Write)(*slot);
  });
  if (!accepted) (this->*Pool)->release(slot);
  return accepted;
}

StepOutputs::Frame* StepOutputs::acquire_frame() {
  Frame* slot = frames_->acquire();
  if (slot == nullptr) ++frames_without_slot_;
  return slot;
}

void StepOutputs::release_frame(Frame* frame) { frames_->release(frame); }

bool StepOutputs::submit_png(std::size_t view, std::int64_t step, Frame* slot) {
  slot->view = view;
  slot->step = step;
  return submit<FrameSlot, &StepOutputs::frames_, &StepOutputs::write_png_job>(slot, "PNG frame");
}

void StepOutputs::write_png_job(FrameSlot& s) {
  const ImageRGBA8 srgb = linear_to_srgb8(s.image.rgba, s.image.width, s.image.height);
  write_png(png_folder_ / step_file_name(view_names_[s.view], s.step, "png"), srgb,
            config_.writer.fsync);
  ++png_written_;
}

bool StepOutputs::submit_stats(const StatsRecord& record) {
  StatsSlot* slot = stats_slots_->acquire();
  if (slot == nullptr || !stats_log_) {
    stats_slots_->release(slot);
    return false;
  }
  slot->line.clear();
  append_json_line(record, slot->line);
  return submit<StatsSlot, &StepOutputs::stats_slots_, &StepOutputs::write_stats_job>(
      slot, "stats line");
}

void StepOutputs::write_stats_job(StatsSlot& s) {
  stats_log_->append(s.line);
  ++stats_written_;
}

void StepOutputs::copy_snapshot(const StepData& data, const std::vector<std::string>& names,
                                double radius, SnapshotSlot& slot) const {
  slot.step = data.step;
  slot.time = data.time;
  slot.spheres.assign(data.boundary.begin(), data.boundary.end());
  if (radius > 0)
    for (ParticleSphere& s : slot.spheres) s.radius = float(radius);
  slot.attributes.resize(names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto found = std::find_if(data.attributes.begin(), data.attributes.end(),
                                    [&](const CompactedAttribute& a) { return a.name == names[k]; });
    if (found == data.attributes.end())
      throw make_error("attribute \"", names[k], "\" was not compacted by the adapter");
    NamedAttribute& a = slot.attributes[k];
    a.name.assign(found->name);
    a.components = found->components;
    a.values.assign(found->values.begin(), found->values.end());
  }
  const CellStatesView& c = data.cells;
  slot.cells.origin = c.origin;
  slot.cells.cell_size = c.cell_size;
  slot.cells.dims = c.dims;
  if (c.empty())
    slot.cells.states.clear();
  else
    slot.cells.states.assign(c.states, c.states + c.cell_count());
}

StepOutputs::SnapshotSlot* StepOutputs::filled_snapshot(SlotPool<SnapshotSlot>& pool,
                                                        const StepData& data,
                                                        const std::vector<std::string>& names,
                                                        double radius) const {
  SnapshotSlot* slot = pool.acquire();
  if (slot == nullptr) return nullptr;
  try {
    copy_snapshot(data, names, radius, *slot);
  } catch (...) {
    pool.release(slot);
    throw;
  }
  return slot;
}

bool StepOutputs::submit_vdb(const StepData& data) {
  SnapshotSlot* slot = filled_snapshot(*vdb_slots_, data, config_.outputs.vdb.attributes, vdb_radius_);
  return slot != nullptr && submit<SnapshotSlot, &StepOutputs::vdb_slots_, &StepOutputs::write_vdb_job>(
      slot, "VDB snapshot");
}

void StepOutputs::write_vdb_job(SnapshotSlot& s) {
  const std::vector<AttributeSpan> attributes = s.attribute_views();
  write_vdb_snapshot(vdb_folder_ / step_file_name("fluid", s.step, "vdb"),
                     {s.spheres, s.cells.view(), attributes, s.step, s.time},
                     VdbSnapshotSettings::from(config_.outputs.vdb), config_.writer.fsync);
  ++vdb_written_;
}

bool StepOutputs::submit_vtk(const StepData& data) {
  SnapshotSlot* slot = filled_snapshot(*vtk_slots_, data, config_.outputs.vtk.attributes, 0);
  return slot != nullptr && submit<SnapshotSlot, &StepOutputs::vtk_slots_, &StepOutputs::write_vtk_job>(
      slot, "VTK files");
}

void StepOutputs::write_vtk_job(SnapshotSlot& s) {
  const bool sync = config_.writer.fsync;
  if (particles_pvd_) {
    const std::string name = step_file_name("particles", s.step, "vtp");
    const std::vector<AttributeSpan> attributes = s.attribute_views();
    write_vtp(vtk_folder_ / name, s.spheres, attributes, sync);
    particles_pvd_->add(s.time, name);
  }
  if (cells_pvd_ && !s.cells.states.empty()) {
    const std::string name = step_file_name("cells", s.step, "vti");
    write_vti(vtk_folder_ / name, s.cells.view(), sync);
    cells_pvd_->add(s.time, name);
  }
  ++vtk_written_;
}

}  // namespace voxspan
