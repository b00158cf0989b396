// Ground truth made in code for environment matting (issue 8): pinhole photos of a mirrored
// sphere resting on a floor that carries a graphic, and of a glass of water in front of a
// backdrop carrying it, ray traced exactly. For a photo pixel the
// tracer returns the graphic pixel seen in the sphere's reflection, which gives exact matches
// (graphic → photo) and the exact image of an inserted graphic.
#pragma once

#include <Eigen/Geometry>

#include <cmath>
#include <optional>

namespace artcam::test {

struct MirrorSphereScene {
  int photo_width = 320, photo_height = 240;
  double focal_px = 600.0;
  Eigen::Vector3d eye{0.0, 2.2, 5.5};
  Eigen::Vector3d look_at{0.0, 0.9, 0.0};
  Eigen::Vector3d sphere_centre{0.0, 1.0, 0.0};
  double sphere_radius = 1.0;
  // The graphic lies on the floor y = 0 over x, z ∈ [-half, half], graphic_size pixels wide.
  double floor_half = 2.0;
  int graphic_size = 512;

  // Graphic pixel (u, v) reflected at photo pixel p (pixel centres at i + 0.5); empty when the
  // ray misses the sphere or its reflection misses the graphic.
  std::optional<Eigen::Vector2d> graphicFromPhoto(const Eigen::Vector2d& p) const {
    const Eigen::Vector3d forward = (look_at - eye).normalized();
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d up = right.cross(forward);
    const Eigen::Vector3d d = (forward + (p.x() - 0.5 * photo_width) / focal_px * right -
                               (p.y() - 0.5 * photo_height) / focal_px * up)
                                  .normalized();
    // Ray–sphere: |eye + t d - c|² = r².
    const Eigen::Vector3d oc = eye - sphere_centre;
    const double b = oc.dot(d);
    const double disc = b * b - (oc.squaredNorm() - sphere_radius * sphere_radius);
    if (disc <= 0.0) return std::nullopt;
    const double t = -b - std::sqrt(disc);
    if (t <= 0.0) return std::nullopt;
    const Eigen::Vector3d hit = eye + t * d;
    const Eigen::Vector3d n = (hit - sphere_centre).normalized();
    const Eigen::Vector3d r = d - 2.0 * d.dot(n) * n;
    if (r.y() >= -1e-9) return std::nullopt;  // reflected upwards: sky, not floor
    const double s = -hit.y() / r.y();
    const Eigen::Vector3d floor = hit + s * r;
    const double u = (floor.x() + floor_half) / (2.0 * floor_half) * graphic_size;
    const double v = (floor.z() + floor_half) / (2.0 * floor_half) * graphic_size;
    if (u < 0.0 || v < 0.0 || u > graphic_size || v > graphic_size) return std::nullopt;
    return Eigen::Vector2d(u, v);
  }
};

// A glass of water (a vertical cylinder of water, the glass wall ignored) in front of a
// vertical backdrop carrying the graphic; the photo sees the backdrop refracted twice
// (Snell's law at entry and exit), flipped and magnified, as in the paper's Fig 8.
struct WaterGlassScene {
  int photo_width = 320, photo_height = 240;
  double focal_px = 300.0;
  Eigen::Vector3d eye{0.0, 0.0, 6.0};  // looking down -z
  double radius = 1.2;                 // axis: the y axis
  double water_index = 1.333;
  double backdrop_z = -1.6;
  double backdrop_half = 1.5;  // the graphic covers x, y ∈ [-half, half] on the backdrop
  // The marked refracting region: rays entering the water within this fraction of the radius
  // from the axis. Nearer the silhouette the map folds over (grazing rays), as it does in a
  // real glass; a user marks the region inside it.
  double region_fraction = 0.5;
  int graphic_size = 512;

  std::optional<Eigen::Vector3d> refract(const Eigen::Vector3d& d, Eigen::Vector3d n, double eta) const {
    double cosi = -n.dot(d);
    if (cosi < 0.0) {  // leaving: flip the normal
      n = -n;
      cosi = -cosi;
    }
    const double k = 1.0 - eta * eta * (1.0 - cosi * cosi);
    if (k < 0.0) return std::nullopt;  // total internal reflection
    return (eta * d + (eta * cosi - std::sqrt(k)) * n).normalized();
  }

  // Ray–cylinder (x² + z² = r²): the far (exit) or near (entry) root along o + t d.
  std::optional<double> cylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, bool far) const {
    const double a = d.x() * d.x() + d.z() * d.z();
    const double b = o.x() * d.x() + o.z() * d.z();
    const double c = o.x() * o.x() + o.z() * o.z() - radius * radius;
    const double disc = b * b - a * c;
    if (a <= 0.0 || disc <= 0.0) return std::nullopt;
    const double t = far ? (-b + std::sqrt(disc)) / a : (-b - std::sqrt(disc)) / a;
    if (t <= 1e-12) return std::nullopt;
    return t;
  }

  std::optional<Eigen::Vector2d> graphicFromPhoto(const Eigen::Vector2d& p) const {
    Eigen::Vector3d d((p.x() - 0.5 * photo_width) / focal_px, -(p.y() - 0.5 * photo_height) / focal_px, -1.0);
    d.normalize();
    const auto t_in = cylinder(eye, d, false);
    if (!t_in) return std::nullopt;
    const Eigen::Vector3d a = eye + *t_in * d;
    if (std::abs(a.x()) > region_fraction * radius) return std::nullopt;
    const auto d_water = refract(d, Eigen::Vector3d(a.x(), 0.0, a.z()).normalized(), 1.0 / water_index);
    if (!d_water) return std::nullopt;
    const auto t_out = cylinder(a, *d_water, true);
    if (!t_out) return std::nullopt;
    const Eigen::Vector3d b = a + *t_out * *d_water;
    const auto d_air = refract(*d_water, Eigen::Vector3d(b.x(), 0.0, b.z()).normalized(), water_index);
    if (!d_air || d_air->z() >= 0.0) return std::nullopt;
    const double s = (backdrop_z - b.z()) / d_air->z();
    const Eigen::Vector3d hit = b + s * *d_air;
    const double u = (hit.x() + backdrop_half) / (2.0 * backdrop_half) * graphic_size;
    const double v = (backdrop_half - hit.y()) / (2.0 * backdrop_half) * graphic_size;
    if (u < 0.0 || v < 0.0 || u > graphic_size || v > graphic_size) return std::nullopt;
    return Eigen::Vector2d(u, v);
  }
};

}  // namespace artcam::test
