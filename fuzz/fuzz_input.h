// Decoding fuzzer bytes into the library's inputs, shared by the narrow-phase and world fuzzers.
//
// Every value is read from the front of the input; past its end the reader returns zeros, so any
// byte string decodes to something and libFuzzer can grow an input one field at a time. Most
// values come from a sane range, but a selector byte lets the fuzzer reach the extremes a game can
// hand the library by mistake: huge and tiny magnitudes, zero, denormals, NaN and infinity. Shapes
// can be degenerate on purpose: coplanar or duplicated hull points, zero-area mesh triangles.
// What must hold for such input is the API's contract: a result, or collide::Error (never a
// crash, a sanitizer report, or another exception).
#pragma once

#include <collide/shapes.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace collide::fuzz {

class FuzzInput {
 public:
  // The first byte decides whether this input may use extreme values at all: half the inputs stay
  // within the sane ranges throughout, so that the checks that only hold there (FuzzInput::sawExtreme)
  // apply to whole stories, not only to the rare ones that never pick an extreme.
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {
    extremesAllowed_ = byte() & 1;
  }

  bool empty() const { return at_ >= size_; }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  bool flag() { return byte() & 1; }
  // An integer in [0, count).
  int choice(int count) { return byte() % count; }

  // A float in [lo, hi], 65,536 steps.
  float range(float lo, float hi) {
    const unsigned high = byte();
    const unsigned v = high << 8 | byte();
    return lo + (hi - lo) * float(v) / 65535.0f;
  }

  // Mostly a float in [lo, hi]; where extremes are allowed, one selector value in eight gives an
  // extreme instead.
  float value(float lo, float hi) {
    const std::uint8_t selector = byte();
    if (selector < 224 || !extremesAllowed_) return range(lo, hi);
    const float v = extreme(selector - 224);
    if (!(v >= lo && v <= hi)) extreme_ = true;
    return v;
  }
  // Whether any value so far came from outside its sane range (the extremes above). Float
  // precision bounds what a query can answer there: a 1e15 m ellipsoid against a 1 m capsule
  // has support points only accurate to 1e8 m. So the fuzzers check accuracy (contracts that
  // compare two answers) only for sane input, and safety (no crash, finite results) for all.
  bool sawExtreme() const { return extreme_; }
  Vec3 vec(float lo, float hi) {
    const float x = value(lo, hi), y = value(lo, hi);
    return Vec3(x, y, value(lo, hi));
  }

  // A rotation: usually a unit quaternion, sometimes one that is not (the API must refuse it).
  Quat rotation() {
    // One read per statement: the order of a call's arguments is unspecified (GCC and clang differ),
    // and a finding must decode the same under both.
    const float w = range(-1, 1), x = range(-1, 1), y = range(-1, 1), z = range(-1, 1);
    Quat q(w, x, y, z);
    if (byte() >= 240) return Quat(value(-1, 1), q.x, q.y, q.z);
    return glm::length(q) < 0.1f ? Quat(1, 0, 0, 0) : glm::normalize(q);
  }

  Transform transform(float positionRange) {
    Transform t;
    t.position = vec(-positionRange, positionRange);
    t.rotation = rotation();
    t.scale = byte() >= 224 ? value(0.5f, 2.0f) : 1.0f;
    return t;
  }

 private:
  // Magnitudes a game reaches by mistake (a unit error, an uninitialised value, a division by a
  // tiny number), positive and negative.
  static float extreme(int which) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    static constexpr std::array<float, 32> kExtremes = {
        0.0f,  -0.0f,  1e-38f, -1e-38f, 1e-45f, 1e-30f, 1e-12f, 1e-7f, 1e-4f,  -1e-4f, 1e4f,
        -1e4f, 1e6f,   -1e6f,  1e9f,    -1e9f,  1e15f,  -1e15f, 1e20f, -1e20f, 1e30f,  -1e30f,
        3e38f, -3e38f, kInf,   -kInf,   kInf,   -kInf,  -1.0f,  -0.5f, 1.0f,   0.0f};
    if (which == 26 || which == 27) return std::numeric_limits<float>::quiet_NaN();
    return kExtremes[which];
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
  bool extremesAllowed_ = false;
  bool extreme_ = false;
};

// Points for a hull or a k-DOP: 4-12 of them, sometimes all on one plane, on one line or on one
// point (the builders must refuse those), sometimes with duplicates.
inline std::vector<Vec3> decodePoints(FuzzInput& in, float size) {
  std::vector<Vec3> points(4 + in.choice(9));
  const int degeneracy = in.choice(8);
  for (Vec3& p : points) {
    p = in.vec(-size, size);
    if (degeneracy == 1) p.z = 0.0f;          // coplanar
    if (degeneracy == 2) p.y = p.z = 0.0f;    // collinear
    if (degeneracy == 3) p = points.front();  // one point
    if (degeneracy == 4) p.z = 1e-7f * p.z;   // nearly coplanar
  }
  if (degeneracy == 5) points[1] = points[0];  // a duplicate
  return points;
}

// A triangle mesh of 1-8 triangles over 3-10 vertices; indices may repeat (zero-area triangles)
// or run past the vertices (out of range): both must be refused.
inline TriangleMesh decodeMesh(FuzzInput& in, float size) {
  std::vector<Vec3> vertices(3 + in.choice(8));
  const bool flat = in.flag();
  for (Vec3& v : vertices) {
    v = in.vec(-size, size);
    if (flat) v.y = 0.0f;
  }
  std::vector<MeshTriangle> triangles(1 + in.choice(8));
  for (MeshTriangle& t : triangles) {
    for (std::uint32_t& index : t.v) index = in.choice(int(vertices.size()) + 1);
  }
  return TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles));
}

// One shape of any type. `allowPlane` is false where the API never takes a plane (a compound's
// child, a moving body); `depth` bounds compound nesting.
inline Shape decodeShape(FuzzInput& in, bool allowPlane, int depth = 0) {
  const float size = 2.0f;
  switch (in.choice(kShapeTypeCount)) {
    case 0:
      return Sphere{in.value(0.01f, size)};
    case 1: {
      const float radius = in.value(0.01f, size);
      return Capsule{radius, in.value(0.0f, size)};
    }
    case 2:
      if (allowPlane) {
        Vec3 normal = in.vec(-1.0f, 1.0f);
        // A unit normal usually; the raw vector sometimes (the constructor must refuse it).
        if (in.byte() < 224 && glm::length(normal) > 0.1f && std::isfinite(glm::length(normal))) {
          normal = glm::normalize(normal);
        }
        return Plane{normal, in.value(-size, size)};
      }
      return Sphere{in.value(0.01f, size)};
    case 3:
      return Box{in.vec(0.01f, size)};
    case 4: {
      static constexpr std::array<int, 5> kK = {6, 14, 18, 26, 10};  // 10: unsupported
      const int k = kK[in.choice(5)];
      return Kdop::fromPoints(k, decodePoints(in, size));
    }
    case 5:
      return Ellipsoid{in.vec(0.01f, size)};
    case 6: {
      const float radius = in.value(0.01f, size);
      return Cylinder{radius, in.value(0.01f, size)};
    }
    case 7:
      return ConvexHull::fromPoints(decodePoints(in, size));
    case 8:
      return decodeMesh(in, size);
    default: {
      if (depth >= 2) return Box{in.vec(0.01f, size)};
      std::vector<Compound::Child> children;
      const int count = 1 + in.choice(3);
      for (int i = 0; i < count; ++i) {
        Shape child = decodeShape(in, /*allowPlane=*/in.byte() >= 250, depth + 1);
        children.push_back({std::move(child), in.transform(size)});
      }
      return Compound::fromChildren(std::move(children));
    }
  }
}

// With COLLIDE_FUZZ_TRACE set in the environment, the fuzzers print what they decode and call, so
// that a finding can be read and turned into a regression test (docs/reliability.md).
inline bool tracing() {
  static const bool on = std::getenv("COLLIDE_FUZZ_TRACE") != nullptr;
  return on;
}

inline std::string describe(float v) {
  std::ostringstream out;
  out.precision(9);
  out << v;
  return out.str();
}
inline std::string describe(const Vec3& v) {
  return "(" + describe(v.x) + ", " + describe(v.y) + ", " + describe(v.z) + ")";
}
inline std::string describe(const Quat& q) {
  return "(w " + describe(q.w) + ", " + describe(q.x) + ", " + describe(q.y) + ", " + describe(q.z) + ")";
}
inline std::string describe(const Transform& t) {
  return "{position " + describe(t.position) + ", rotation " + describe(t.rotation) + ", scale " +
         describe(t.scale) + "}";
}
inline std::string describe(const Shape& shape) {
  std::string text(toString(shape.type()));
  const auto points = [&](std::span<const Vec3> vertices) {
    for (const Vec3& v : vertices) text += " " + describe(v);
  };
  switch (shape.type()) {
    case ShapeType::Sphere:
      return text + " radius " + describe(shape.sphere().radius);
    case ShapeType::Capsule:
      return text + " radius " + describe(shape.capsule().radius) + " halfHeight " +
             describe(shape.capsule().halfHeight);
    case ShapeType::Plane:
      return text + " normal " + describe(shape.plane().normal) + " distance " +
             describe(shape.plane().distance);
    case ShapeType::Box:
      return text + " halfExtents " + describe(shape.box().halfExtents);
    case ShapeType::Ellipsoid:
      return text + " radii " + describe(shape.ellipsoid().radii);
    case ShapeType::Cylinder:
      return text + " radius " + describe(shape.cylinder().radius) + " halfHeight " +
             describe(shape.cylinder().halfHeight);
    case ShapeType::Kdop:
      text += " k " + std::to_string(shape.kdop().k()) + ", polytope";
      points(shape.kdop().polytope().vertices());
      return text;
    case ShapeType::ConvexHull:
      points(shape.convexHull().vertices());
      return text;
    case ShapeType::Mesh:
      points(shape.mesh().vertices());
      text += ", triangles";
      for (const MeshTriangle& t : shape.mesh().triangles()) {
        text +=
            " [" + std::to_string(t.v[0]) + " " + std::to_string(t.v[1]) + " " + std::to_string(t.v[2]) + "]";
      }
      return text;
    case ShapeType::Compound:
      text += " {";
      for (const Compound::Child& child : shape.compound().children()) {
        text += " " + describe(child.shape) + " at " + describe(child.transform) + ";";
      }
      return text + " }";
  }
  return text;
}

}  // namespace collide::fuzz
