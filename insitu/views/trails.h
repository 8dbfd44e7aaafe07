// insitu/views/trails.h - the paths of chosen particles over the last render steps, drawn as
// lines into a 3D view's picture, hidden where the view shows something nearer. Particles are
// told apart by an id attribute the solver passes (they move between ranks and solvers reorder
// them); the view picks those whose id is a multiple of `every`, or those listed. The trails
// live where the picture is made (rank 0 of an MPI job: every rank sends its chosen owned
// particles' positions each render step, so a particle's trail survives its migrations).
#pragma once

#include <cstdint>
#include <span>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "render/camera.h"
#include "render/float_image.h"
#include "voxspan/particles.h"

namespace voxspan {

// Which particles have trails and how long they are.
struct TrailChoice {
  std::string_view id;                 // the id attribute
  std::string_view key = "trails.id";  // the key that names it, for messages
  std::int64_t every = 0;              // ids that are multiples of it (0: none)
  std::span<const std::int64_t> ids;   // and these, sorted
  bool any() const { return every > 0 || !ids.empty(); }
};

struct TrailPoint {
  double id, x, y, z;  // the id as the solver passes it (a float or double attribute)
};

// This rank's chosen owned particles with finite positions and ids, into `out` (storage reused).
// Throws voxspan::Error naming the attribute when the solver does not pass it.
void collect_trail_points(const ParticleView& particles, const TrailChoice& choice,
                          std::vector<TrailPoint>& out);

class Trails {
 public:
  explicit Trails(int length) : length_(length) {}
  // One render step's points (every rank's); trails not seen for `length` steps are dropped.
  void add_step(std::span<const TrailPoint> points);
  // The trails as lines, brightest at their newest point, fading to nothing at their oldest;
  // `depth` holds each pixel's view depth (0: nothing there), which hides a line behind it.
  void draw(const Camera& camera, std::span<const float> depth, glm::vec3 colour,
            FloatImage& picture) const;
  std::size_t count() const { return trails_.size(); }

 private:
  struct Trail {
    std::vector<glm::dvec3> points;  // oldest first, at most length_
    std::int64_t last_step = 0;
  };
  int length_;
  std::int64_t step_ = 0;
  std::map<std::int64_t, Trail> trails_;  // by id: drawn in a fixed order
};

}  // namespace voxspan
