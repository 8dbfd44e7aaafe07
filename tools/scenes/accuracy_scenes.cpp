#include "tools/scenes/accuracy_scenes.h"

namespace voxspan::test {

std::vector<AccuracyScene> accuracy_scenes(int width, int height) {
  std::vector<AccuracyScene> scenes;
  const auto add = [&](std::string name, Particles particles, glm::dvec3 direction) {
    AccuracyScene s;
    s.name = std::move(name);
    s.particles = std::move(particles);
    s.camera = frame_scene(s.particles, direction, width, height);
    scenes.push_back(std::move(s));
    return &scenes.back();
  };
  add("one sphere", one_sphere({0.1, 0.6, 0.2}, 0.5), {0.3, -0.2, -1});
  add("lattice block", lattice_block({0, 0, 0}, {12, 10, 8}, 0.1, 0.09), {0.5, -0.4, -1});
  {
    DamBreak shape;
    shape.spacing = 0.02;
    shape.radius = 0.02;
    AccuracyScene* s = add("dam break", dam_break(shape, 0.15), {0.4, -0.5, -1});
    s->options.gap_bridging = shape.spacing;
  }
  {
    AccuracyScene* s =
        add("24 layers, cap 7", stacked_layers(24, 24, 2, 0.05, 0.045, 0.2), {0, 0, 1});
    s->camera = look_at({0.62, 0.58, -1.2}, {0.6, 0.6, 1.0}, width, height);
    s->options.max_spans = 7;
    s->options.gap_bridging = 0.025;
  }
  {
    AccuracyScene* s = add("checkerboard", checkerboard(6, 4, 0.05, 0.045), {0.6, -0.5, -1});
    s->options.max_spans = 7;
    s->options.gap_bridging = 0.025;
  }
  add("random cloud", random_cloud(400, {0, 0, 0}, {1, 1, 1}, 0.01, 0.1, 1), {0.2, 0.3, -1});
  return scenes;
}

ShadeOptions test_shading(ShadeMode mode, double tile) {
  ShadeOptions o;
  o.mode = mode;
  o.material.absorption = {3.0, 1.2, 0.5};
  o.material.scatter_color = {0.04, 0.1, 0.16};
  o.environment.ground_tile = tile;
  return o;
}

}  // namespace voxspan::test
