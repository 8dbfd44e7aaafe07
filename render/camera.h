// render/camera.h - a pinhole camera as a solver user states it: eye, target, up, vertical field
// of view and image size. Pixel (x, y) has row y = 0 at the top of the image (the order images
// are written in); its ray passes through the pixel's centre.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace voxspan {

struct Camera {
  glm::dvec3 eye{0, 0, 5};
  glm::dvec3 target{0, 0, 0};
  glm::dvec3 up{0, 1, 0};
  double fov_y_degrees = 45;
  int width = 960;
  int height = 540;
  bool operator==(const Camera&) const = default;
};

// The camera turned about its target: by `phi_degrees` about its `up`, then raised by
// `theta_degrees` towards it, at the same distance (0, 0: the camera itself). The elevation
// stops 1 degree short of `up` (and of its opposite), where the camera would have no frame.
Camera orbited(const Camera& camera, double phi_degrees, double theta_degrees);
// The same turn with eye and target carried about `pivot` together, so that `pivot` stays where
// the picture shows it (a camera framed beside a colour bar keeps the fluid clear of it).
Camera orbited(const Camera& camera, double phi_degrees, double theta_degrees, glm::dvec3 pivot);

// Throws voxspan::Error naming the field when the camera cannot form an image (non-finite
// vectors, eye on target, up along the view direction, fov outside (0, 180), size < 1 or above
// 16384).
void validate(const Camera& camera);

// The camera's orthonormal frame and the slopes of its image plane. View space: x right, y up,
// z = depth along `forward` (positive in front of the eye).
struct ViewFrame {
  glm::dvec3 eye{0}, right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, -1};
  double tan_half_x = 1, tan_half_y = 1;      // image-plane half extents at depth 1
  double side_scale_x = 1, side_scale_y = 1;  // 1 / |normal| of the side planes x, y = +-tan z
  int width = 1, height = 1;

  explicit ViewFrame(const Camera& camera);
  ViewFrame() = default;

  glm::dvec3 to_view(glm::dvec3 world) const {
    const glm::dvec3 d = world - eye;
    return {glm::dot(d, right), glm::dot(d, up), glm::dot(d, forward)};
  }
  // View-space ray through the centre of pixel (x, y), scaled so that its depth component is 1:
  // the point at depth z on the ray is z * view_ray(x, y).
  glm::dvec3 view_ray(int x, int y) const {
    const double ndc_x = 2.0 * (x + 0.5) / width - 1.0;
    const double ndc_y = 1.0 - 2.0 * (y + 0.5) / height;
    return {ndc_x * tan_half_x, ndc_y * tan_half_y, 1.0};
  }
  // view_ray's inverse: the continuous pixel coordinates (pixel k's centre at k, rows growing
  // downwards) of image-plane slopes x / z and y / z.
  double pixel_x(double slope_x) const { return (slope_x / tan_half_x + 1) * 0.5 * width - 0.5; }
  double pixel_y(double slope_y) const { return (1 - slope_y / tan_half_y) * 0.5 * height - 0.5; }
  // The same ray in world space (eye + z * world_ray is the point at depth z).
  glm::dvec3 world_ray(int x, int y) const {
    const glm::dvec3 v = view_ray(x, y);
    return v.x * right + v.y * up + forward;
  }
  // Whether a view-space sphere reaches into the view pyramid (in front of the eye, inside the
  // four side planes). Spheres passing it may still miss every pixel centre.
  bool meets_pyramid(glm::dvec3 c, double r) const {
    return c.z + r > 0 && (std::abs(c.x) - tan_half_x * c.z) * side_scale_x < r &&
           (std::abs(c.y) - tan_half_y * c.z) * side_scale_y < r;
  }
  // World length of the ray per unit of depth: a depth interval dz is dz * ray_scale long.
  double ray_scale(int x, int y) const { return glm::length(view_ray(x, y)); }
};

}  // namespace voxspan
