// Narrow-phase fuzzer: two shapes (sphere, capsule, box, convex hull of 4-8 points, plane) with
// bounded sizes and arbitrary placements, decoded from the bytes, through collide() and, for convex
// pairs, distance(). Allowed: a result, or collide::Error for what the API documents (a degenerate
// hull, plane-plane). Checked: at most 4 points, a unit normal, finite points and depths.
#include <collide/narrowphase.h>
#include <collide/shapes.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace {

using namespace collide;

struct Bytes {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at = 0;
  std::uint8_t byte() { return at < size ? data[at++] : 0; }
  // A float in [lo, hi] from two bytes.
  float range(float lo, float hi) {
    const unsigned v = unsigned(byte()) << 8 | byte();
    return lo + (hi - lo) * float(v) / 65535.0f;
  }
  Vec3 vec(float lo, float hi) {
    const float x = range(lo, hi), y = range(lo, hi);
    return Vec3(x, y, range(lo, hi));
  }
};

Shape decodeShape(Bytes& in, bool& isPlane) {
  isPlane = false;
  switch (in.byte() % 5) {
    case 0: return Sphere{in.range(0.01f, 2.0f)};
    case 1: {
      const float r = in.range(0.01f, 2.0f);
      return Capsule{r, in.range(0.0f, 2.0f)};
    }
    case 2: return Box{in.vec(0.01f, 2.0f)};
    case 3: {
      std::vector<Vec3> points(4 + in.byte() % 5);
      for (Vec3& p : points) p = in.vec(-1.0f, 1.0f);
      return ConvexHull::fromPoints(points);
    }
    default: {
      isPlane = true;
      Vec3 n = in.vec(-1.0f, 1.0f);
      if (glm::length(n) < 0.1f) n = Vec3(0, 1, 0);
      return Plane{glm::normalize(n), in.range(-2.0f, 2.0f)};
    }
  }
}

Transform decodeTransform(Bytes& in) {
  Transform t;
  t.position = in.vec(-3.0f, 3.0f);
  Quat q(in.range(-1, 1), in.range(-1, 1), in.range(-1, 1), in.range(-1, 1));
  t.rotation = glm::length(q) < 0.1f ? Quat(1, 0, 0, 0) : glm::normalize(q);
  return t;
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in{data, size};
  try {
    bool planeA = false, planeB = false;
    const Shape a = decodeShape(in, planeA);
    const Transform ta = decodeTransform(in);
    const Shape b = decodeShape(in, planeB);
    const Transform tb = decodeTransform(in);
    const float margin = in.range(0.0f, 0.5f);
    Manifold m;
    collide::collide(a, ta, b, tb, m, margin);
    if (m.count < 0 || m.count > Manifold::kMaxPoints) std::abort();
    if (m.count > 0) {
      if (!finite(m.normal) || std::abs(glm::length(m.normal) - 1.0f) > 1e-3f) std::abort();
      for (int i = 0; i < m.count; ++i) {
        if (!std::isfinite(m.points[i].depth)) std::abort();
      }
    }
    if (!(planeA && planeB)) {
      const DistanceResult d = distance(a, ta, b, tb);
      if (!std::isfinite(d.distance) || !finite(d.pointOnA) || !finite(d.pointOnB)) std::abort();
    }
  } catch (const Error&) {
  }
  return 0;
}
