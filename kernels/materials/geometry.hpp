// Scene geometry as point functions: primitives (box, sphere, cylinder, cone frustum, spherical
// shell), combined as (primary ∪ additions) − removals, and the volume fraction of a cell inside
// a shape by sub-cell sampling. Plain data, so a device kernel can hold shapes by value.
#pragma once
#include "core/math.hpp"

namespace mp::geom {

enum Kind : int { kAll = 0, kBox, kSphere, kCylinder, kCone, kShell };

struct Primitive {
  int kind = kAll;
  double a[3] = {0, 0, 0};  // box: low corner; sphere, shell: centre; cylinder, cone: base centre
  double b[3] = {0, 0, 0};  // box: high corner; cylinder, cone: top centre
  double r0 = 0;            // sphere radius; shell inner radius; cylinder radius; cone base radius
  double r1 = 0;            // shell outer radius; cone top radius (0: a pointed cone)

  KOKKOS_INLINE_FUNCTION bool contains(double x, double y, double z) const {
    switch (kind) {
      case kAll:
        return true;
      case kBox:
        return x >= a[0] && x < b[0] && y >= a[1] && y < b[1] && z >= a[2] && z < b[2];
      case kSphere:
      case kShell: {
        const double dx = x - a[0], dy = y - a[1], dz = z - a[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        return kind == kSphere ? d2 < r0 * r0 : (d2 >= r0 * r0 && d2 < r1 * r1);
      }
      default: {  // cylinder and cone frustum about the axis from a to b
        const double ax = b[0] - a[0], ay = b[1] - a[1], az = b[2] - a[2];
        const double len2 = ax * ax + ay * ay + az * az;
        const double px = x - a[0], py = y - a[1], pz = z - a[2];
        const double t = (px * ax + py * ay + pz * az) / len2;  // 0 at the base, 1 at the top
        if (t < 0 || t >= 1) return false;
        const double qx = px - t * ax, qy = py - t * ay, qz = pz - t * az;
        const double r = kind == kCylinder ? r0 : r0 + (r1 - r0) * t;
        return qx * qx + qy * qy + qz * qz < r * r;
      }
    }
  }

  // Axis-aligned bounding box (host and device).
  KOKKOS_INLINE_FUNCTION void bounds(double lo[3], double hi[3]) const {
    for (int d = 0; d < 3; ++d) {
      switch (kind) {
        case kAll:
          lo[d] = -1e300;
          hi[d] = 1e300;
          break;
        case kBox:
          lo[d] = a[d];
          hi[d] = b[d];
          break;
        case kSphere:
          lo[d] = a[d] - r0;
          hi[d] = a[d] + r0;
          break;
        case kShell:
          lo[d] = a[d] - r1;
          hi[d] = a[d] + r1;
          break;
        default: {
          const double r = kind == kCylinder ? r0 : mmax(r0, r1);
          lo[d] = mmin(a[d], b[d]) - r;
          hi[d] = mmax(a[d], b[d]) + r;
        }
      }
    }
  }
};

constexpr int kMaxTerms = 8;

// (primary ∪ add[0] ∪ ...) − remove[0] − ...
struct Shape {
  Primitive primary;
  int n_add = 0, n_remove = 0;
  Primitive add[kMaxTerms];
  Primitive remove[kMaxTerms];

  KOKKOS_INLINE_FUNCTION bool contains(double x, double y, double z) const {
    bool in = primary.contains(x, y, z);
    for (int i = 0; i < n_add && !in; ++i) in = add[i].contains(x, y, z);
    for (int i = 0; i < n_remove && in; ++i) in = !remove[i].contains(x, y, z);
    return in;
  }
  KOKKOS_INLINE_FUNCTION void bounds(double lo[3], double hi[3]) const {
    primary.bounds(lo, hi);
    for (int i = 0; i < n_add; ++i) {
      double l[3], h[3];
      add[i].bounds(l, h);
      for (int d = 0; d < 3; ++d) {
        lo[d] = mmin(lo[d], l[d]);
        hi[d] = mmax(hi[d], h[d]);
      }
    }
  }
};

// Fraction of the cell [lo, lo + h) inside `shape`, from samples^3 points at the centres of a
// uniform sub-grid (samples = 1: the cell centre decides). A cell whose bounding box misses the
// shape's costs one test.
KOKKOS_INLINE_FUNCTION double sampled_fraction(const Shape& shape, const double lo[3],
                                               const double h[3], int samples) {
  double blo[3], bhi[3];
  shape.bounds(blo, bhi);
  for (int d = 0; d < 3; ++d)
    if (lo[d] + h[d] <= blo[d] || lo[d] >= bhi[d]) return 0;
  int inside = 0;
  const double inv = 1.0 / samples;
  for (int k = 0; k < samples; ++k)
    for (int j = 0; j < samples; ++j)
      for (int i = 0; i < samples; ++i)
        if (shape.contains(lo[0] + (i + 0.5) * inv * h[0], lo[1] + (j + 0.5) * inv * h[1],
                           lo[2] + (k + 0.5) * inv * h[2]))
          ++inside;
  return double(inside) / (double(samples) * samples * samples);
}

}  // namespace mp::geom
