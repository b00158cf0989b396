// SPDX-License-Identifier: Apache-2.0
// Scenes made in code for environment matting (the paper's Figs 7 and 8): pinhole
// photos of a mirrored sphere resting on a floor that carries a graphic, and of a glass of
// water in front of a backdrop carrying it, ray traced exactly. For a photo pixel the tracer
// returns the graphic pixel seen in the reflection or refraction: exact matches (graphic →
// photo) and the exact image of an inserted graphic for the tests, and the bundled sample
// photos and grid matches (`artcam sample`).
#pragma once

#include "core/model/fit_record.h"
#include "core/model/image.h"

#include <Eigen/Geometry>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace artcam {

// Where a photo ray ends: on the graphic's plane (its coordinates in graphic pixels, possibly
// outside the graphic) directly or through the object, or in the sky.
struct TracedRay {
  bool on_plane = false;
  bool through_object = false;
  bool in_region = true;  // inside the region a user would mark (where the map does not fold)
  Eigen::Vector2d plane_px = Eigen::Vector2d::Zero();
};

struct MirrorSphereScene {
  int photo_width = 320, photo_height = 240;
  double focal_px = 600.0;
  Eigen::Vector3d eye{0.0, 2.2, 5.5};
  Eigen::Vector3d look_at{0.0, 0.9, 0.0};
  Eigen::Vector3d sphere_centre{0.0, 1.0, 0.0};
  double sphere_radius = 1.0;
  // The graphic lies on the floor y = 0 over x, z ∈ [-half, half], graphic_size pixels wide.
  double floor_half = 2.0;
  double floor_centre_z = 0.0;  // the graphic's centre on the floor is (0, 0, floor_centre_z)
  int graphic_size = 512;

  Eigen::Vector2d floorPx(const Eigen::Vector3d& floor) const {
    return {(floor.x() + floor_half) / (2.0 * floor_half) * graphic_size,
            (floor.z() - floor_centre_z + floor_half) / (2.0 * floor_half) * graphic_size};
  }

  // The point of the floor under graphic pixel g (floorPx's inverse).
  Eigen::Vector3d floorFromGraphicPx(const Eigen::Vector2d& g) const {
    return {g.x() / graphic_size * 2.0 * floor_half - floor_half, 0.0,
            g.y() / graphic_size * 2.0 * floor_half - floor_half + floor_centre_z};
  }

  // The photo pixel where the pinhole sees world point X directly (no occlusion test).
  Eigen::Vector2d photoFromWorld(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d forward = (look_at - eye).normalized();
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d up = right.cross(forward);
    const Eigen::Vector3d v = x - eye;
    const double depth = v.dot(forward);
    return {0.5 * photo_width + focal_px * v.dot(right) / depth,
            0.5 * photo_height - focal_px * v.dot(up) / depth};
  }

  // Where the sphere's centre shows in the photo: a point inside its outline.
  Eigen::Vector2d objectCentrePx() const { return photoFromWorld(sphere_centre); }

  // The unit direction of the ray from the eye through photo pixel p (centres at i + 0.5).
  Eigen::Vector3d rayDirection(const Eigen::Vector2d& p) const {
    const Eigen::Vector3d forward = (look_at - eye).normalized();
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d up = right.cross(forward);
    return (forward + (p.x() - 0.5 * photo_width) / focal_px * right -
            (p.y() - 0.5 * photo_height) / focal_px * up)
        .normalized();
  }

  // The ray through photo pixel p.
  TracedRay trace(const Eigen::Vector2d& p) const {
    const Eigen::Vector3d d = rayDirection(p);
    TracedRay out;
    // Ray–sphere: |eye + t d - c|² = r².
    const Eigen::Vector3d oc = eye - sphere_centre;
    const double b = oc.dot(d);
    const double disc = b * b - (oc.squaredNorm() - sphere_radius * sphere_radius);
    const double t = disc > 0.0 ? -b - std::sqrt(disc) : -1.0;
    if (t > 0.0) {
      out.through_object = true;
      const Eigen::Vector3d hit = eye + t * d;
      const Eigen::Vector3d n = (hit - sphere_centre).normalized();
      const Eigen::Vector3d r = d - 2.0 * d.dot(n) * n;
      if (r.y() >= -1e-9) return out;  // reflected upwards: sky, not floor
      out.on_plane = true;
      out.plane_px = floorPx(hit + (-hit.y() / r.y()) * r);
      return out;
    }
    if (d.y() < 0.0) {
      out.on_plane = true;
      out.plane_px = floorPx(eye + (-eye.y() / d.y()) * d);
    }
    return out;
  }

  // Graphic pixel (u, v) reflected at photo pixel p; empty when the ray misses the sphere or
  // its reflection misses the graphic.
  std::optional<Eigen::Vector2d> graphicFromPhoto(const Eigen::Vector2d& p) const {
    const TracedRay r = trace(p);
    if (!r.through_object || !r.on_plane) return std::nullopt;
    const Eigen::Vector2d& g = r.plane_px;
    if (g.x() < 0.0 || g.y() < 0.0 || g.x() > graphic_size || g.y() > graphic_size) return std::nullopt;
    return g;
  }
};

// Snell's law for unit direction `d` meeting a surface of normal `n` (either side) with index
// ratio eta = n_from / n_to; none on total internal reflection.
inline std::optional<Eigen::Vector3d> refractRay(const Eigen::Vector3d& d, Eigen::Vector3d n,
                                                 double eta) {
  double cosi = -n.dot(d);
  if (cosi < 0.0) {  // leaving: flip the normal
    n = -n;
    cosi = -cosi;
  }
  const double k = 1.0 - eta * eta * (1.0 - cosi * cosi);
  if (k < 0.0) return std::nullopt;  // total internal reflection
  return (eta * d + (eta * cosi - std::sqrt(k)) * n).normalized();
}

// Ray–cylinder x² + z² = r² (axis y): the far (exit) or near (entry) root along o + t·d.
inline std::optional<double> hitVerticalCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                                 double r, bool far) {
  const double a = d.x() * d.x() + d.z() * d.z();
  const double b = o.x() * d.x() + o.z() * d.z();
  const double c = o.x() * o.x() + o.z() * o.z() - r * r;
  const double disc = b * b - a * c;
  if (a <= 0.0 || disc <= 0.0) return std::nullopt;
  const double t = far ? (-b + std::sqrt(disc)) / a : (-b - std::sqrt(disc)) / a;
  if (t <= 1e-12) return std::nullopt;
  return t;
}

// The graphic pixel of a point on a vertical backdrop whose graphic covers x, y ∈ [-half, half].
inline Eigen::Vector2d backdropGraphicPx(const Eigen::Vector3d& hit, double half, int size) {
  return {(hit.x() + half) / (2.0 * half) * size, (half - hit.y()) / (2.0 * half) * size};
}

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

  std::optional<double> cylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, bool far) const {
    return hitVerticalCylinder(o, d, radius, far);
  }
  Eigen::Vector2d backdropPx(const Eigen::Vector3d& hit) const {
    return backdropGraphicPx(hit, backdrop_half, graphic_size);
  }

  // The ray through photo pixel p.
  TracedRay trace(const Eigen::Vector2d& p) const {
    Eigen::Vector3d d((p.x() - 0.5 * photo_width) / focal_px, -(p.y() - 0.5 * photo_height) / focal_px, -1.0);
    d.normalize();
    TracedRay out;
    const auto t_in = cylinder(eye, d, false);
    if (!t_in) {  // the backdrop, seen directly
      out.on_plane = true;
      out.plane_px = backdropPx(eye + ((backdrop_z - eye.z()) / d.z()) * d);
      return out;
    }
    out.through_object = true;
    const Eigen::Vector3d a = eye + *t_in * d;
    out.in_region = std::abs(a.x()) <= region_fraction * radius;
    const auto d_water =
        refractRay(d, Eigen::Vector3d(a.x(), 0.0, a.z()).normalized(), 1.0 / water_index);
    if (!d_water) return out;
    const auto t_out = cylinder(a, *d_water, true);
    if (!t_out) return out;
    const Eigen::Vector3d b = a + *t_out * *d_water;
    const auto d_air =
        refractRay(*d_water, Eigen::Vector3d(b.x(), 0.0, b.z()).normalized(), water_index);
    if (!d_air || d_air->z() >= 0.0) return out;
    out.on_plane = true;
    out.plane_px = backdropPx(b + ((backdrop_z - b.z()) / d_air->z()) * *d_air);
    return out;
  }

  std::optional<Eigen::Vector2d> graphicFromPhoto(const Eigen::Vector2d& p) const {
    const TracedRay r = trace(p);
    if (!r.through_object || !r.on_plane || !r.in_region) return std::nullopt;
    const Eigen::Vector2d& g = r.plane_px;
    if (g.x() < 0.0 || g.y() < 0.0 || g.x() > graphic_size || g.y() > graphic_size) return std::nullopt;
    return g;
  }
};

// The paper's Fig 8 glass whole: a glass (a vertical tube of glass, its wall `wall` thick) filled
// with water up to `water_level` (world y), in front of the backdrop. A ray below the waterline
// passes glass, water, glass; above it glass, air, glass (Snell's law at each of the four
// surfaces), so the photo sees the backdrop through two different refractions, which the
// paper fits with patches of their own (6 through air, 16 through water). `medium` picks which
// of the two graphicFromPhoto answers for; rays whose path inside crosses the water's surface
// (the meniscus band), that meet only the glass wall (near the silhouette) or that enter farther
// than region_fraction of the inner radius from the axis have no image in either.
struct GlassOfWaterScene {
  enum class Medium { Air, Water };
  int photo_width = 320, photo_height = 240;
  double focal_px = 300.0;
  Eigen::Vector3d eye{0.0, 0.0, 6.0};  // looking down -z
  double radius = 1.2;                 // the glass's outside; axis: the y axis
  double wall = 0.06;                  // the glass's thickness
  double glass_index = 1.5;
  double water_index = 1.333;
  double water_level = 0.0;  // world y of the water's surface
  double backdrop_z = -1.6;
  double backdrop_half = 1.5;
  double region_fraction = 0.5;
  int graphic_size = 512;
  Medium medium = Medium::Water;

  static Eigen::Vector3d normalAt(const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.x(), 0.0, p.z()).normalized();
  }
  Eigen::Vector2d backdropPx(const Eigen::Vector3d& hit) const {
    return backdropGraphicPx(hit, backdrop_half, graphic_size);
  }

  // The ray through photo pixel p; `seen` gets the medium it crossed (when it crossed one whole).
  TracedRay trace(const Eigen::Vector2d& p, std::optional<Medium>* seen = nullptr) const {
    Eigen::Vector3d d((p.x() - 0.5 * photo_width) / focal_px,
                      -(p.y() - 0.5 * photo_height) / focal_px, -1.0);
    d.normalize();
    TracedRay out;
    if (seen) seen->reset();
    const auto t_outer = hitVerticalCylinder(eye, d, radius, false);
    if (!t_outer) {
      out.on_plane = true;
      out.plane_px = backdropPx(eye + ((backdrop_z - eye.z()) / d.z()) * d);
      return out;
    }
    out.through_object = true;
    out.in_region = false;
    const double inner = radius - wall;
    const Eigen::Vector3d a = eye + *t_outer * d;  // air → glass
    const auto d1 = refractRay(d, normalAt(a), 1.0 / glass_index);
    if (!d1) return out;
    const auto t_inner = hitVerticalCylinder(a, *d1, inner, false);
    if (!t_inner) return out;                      // only the wall: no image
    const Eigen::Vector3d b = a + *t_inner * *d1;  // glass → medium
    const Medium m = b.y() < water_level ? Medium::Water : Medium::Air;
    const double n_inside = m == Medium::Water ? water_index : 1.0;
    const auto d2 = refractRay(*d1, normalAt(b), glass_index / n_inside);
    if (!d2) return out;
    const auto t_across = hitVerticalCylinder(b, *d2, inner, true);
    if (!t_across) return out;
    const Eigen::Vector3d c = b + *t_across * *d2;  // medium → glass
    // The surface between water and air is crossed: that ray bends at it too (the meniscus
    // band a user leaves out of both regions).
    if ((c.y() < water_level) != (m == Medium::Water)) return out;
    const auto d3 = refractRay(*d2, normalAt(c), n_inside / glass_index);
    if (!d3) return out;
    const auto t_wall = hitVerticalCylinder(c, *d3, radius, true);
    if (!t_wall) return out;
    const Eigen::Vector3d e = c + *t_wall * *d3;  // glass → air
    const auto d4 = refractRay(*d3, normalAt(e), glass_index);
    if (!d4 || d4->z() >= 0.0) return out;
    out.on_plane = true;
    out.plane_px = backdropPx(e + ((backdrop_z - e.z()) / d4->z()) * *d4);
    out.in_region = std::abs(b.x()) <= region_fraction * inner;
    if (seen) *seen = m;
    return out;
  }

  std::optional<Eigen::Vector2d> graphicFromPhoto(const Eigen::Vector2d& p) const {
    std::optional<Medium> seen;
    const TracedRay r = trace(p, &seen);
    if (!r.through_object || !r.on_plane || !r.in_region || seen != medium) return std::nullopt;
    const Eigen::Vector2d& g = r.plane_px;
    if (g.x() < 0.0 || g.y() < 0.0 || g.x() > graphic_size || g.y() > graphic_size)
      return std::nullopt;
    return g;
  }
};

// The bundled samples (`artcam sample`): a photo of the scene whose graphic plane carries a
// calibration checkerboard of `squares` × `squares` (linear float RGB, 3×3 supersampled),
// and the grid's corners seen through the object as matches (graphic pixels → photo pixels),
// each found by Newton's method on the tracer to 1e-6 graphic px.
//
// The mirror-sphere sample also carries what Fig 7 needs to put the graphic on the table as well
// as in its reflection: four grid corners the photo sees directly, as a user would click them
// (graphic pixels → exact pinhole projections in photo pixels; inside the frame, not hidden by
// the sphere, as far apart as the frame allows), from which the board → photo homography is
// fitted (Fig 7b); and the sphere's outline in the photo (a polygon of photo pixels, its
// vertices on the traced silhouette to 1e-6 px), the region where the object hides the table
// and shows the reflection.
struct SampleScene {
  ImageF photo;
  std::vector<PointMatch> grid_matches;
  std::vector<PointMatch> table_matches;  // mirror sphere only
  std::vector<Eigen::Vector2d> region;    // mirror sphere only
  std::vector<PointMatch> air_matches;    // glass of water only: the grid seen above the water
};
SampleScene makeMirrorSphereSample(const MirrorSphereScene& scene, int squares);
SampleScene makeWaterGlassSample(const WaterGlassScene& scene, int squares);
// The glass with its waterline: grid_matches through the water, air_matches through the air
// above it (scene.medium is ignored).
SampleScene makeGlassOfWaterSample(GlassOfWaterScene scene, int squares);

// A graphic to insert: a colourful emblem with premultiplied alpha (a ring and a star).
ImageF makeEmblemGraphic(int size);

}  // namespace artcam
