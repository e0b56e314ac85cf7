// The exact minimal enclosing sphere (Welzl, "Smallest enclosing disks (balls and ellipsoids)", 1991),
// with the move-to-front heuristic of the same paper as refined by Gärtner ("Fast and robust smallest
// enclosing balls", ESA 1999): a point found outside the current ball moves to the front of the list,
// so the points that define the answer are tried first on later passes. The recursion depth is bounded
// by the support set: at most 4 points in 3D.
#include <collide/bounding.h>

#include "bounding/point_set.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <list>
#include <vector>

namespace collide {

namespace {

using DVec3 = glm::dvec3;

struct Ball {
  DVec3 center{0.0};
  double radiusSquared = -1.0;  // negative: the empty ball, which contains nothing
};

// Points within this fraction of the set's size outside a ball count as inside. It absorbs the
// double rounding of the circumcentre formulas (~1e-16 times their conditioning) so that a point on
// the boundary, or a duplicate of a support point, never enters the support set twice; the final
// radius is measured over all points, so the answer still contains them.
constexpr double kRelativeTolerance = 1e-10;

Ball diametral(const DVec3& a, const DVec3& b) {
  const DVec3 c = 0.5 * (a + b);
  return {c, glm::dot(a - c, a - c)};
}

bool containsAll(const Ball& ball, std::span<const DVec3> points, double tolerance) {
  if (ball.radiusSquared < 0.0) return false;
  const double r = std::sqrt(ball.radiusSquared) + tolerance;
  for (const DVec3& p : points)
    if (glm::dot(p - ball.center, p - ball.center) > r * r) return false;
  return true;
}

// The circle through three points (the sphere centred in their plane), or nothing when they are
// collinear: sin(angle at a) below 1e-12 is collinear in double (float input that is collinear in
// exact arithmetic gives exactly 0).
bool circumcircle(const DVec3& a, const DVec3& b, const DVec3& c, Ball& out) {
  const DVec3 ab = b - a, ac = c - a;
  const DVec3 n = glm::cross(ab, ac);
  const double n2 = glm::dot(n, n);
  if (n2 <= 1e-24 * glm::dot(ab, ab) * glm::dot(ac, ac)) return false;
  // Centre = a + (|ac|^2 (n x ab) + |ab|^2 (ac x n)) / (2 |n|^2): equidistant from a, b, c and in
  // their plane.
  const DVec3 offset =
      (glm::dot(ac, ac) * glm::cross(n, ab) + glm::dot(ab, ab) * glm::cross(ac, n)) / (2.0 * n2);
  out = {a + offset, glm::dot(offset, offset)};
  return true;
}

// The sphere through four points, or nothing when they are coplanar: |det| relative to the product
// of the edge lengths below 1e-12.
bool circumsphere(const DVec3& a, const DVec3& b, const DVec3& c, const DVec3& d, Ball& out) {
  const DVec3 ab = b - a, ac = c - a, ad = d - a;
  const double det = glm::dot(ab, glm::cross(ac, ad));
  const double lengths = glm::length(ab) * glm::length(ac) * glm::length(ad);
  if (std::abs(det) <= 1e-12 * lengths) return false;
  // Solve 2 [ab; ac; ad] x = [|ab|^2; |ac|^2; |ad|^2] by Cramer's rule in cross-product form.
  const DVec3 offset = (glm::dot(ab, ab) * glm::cross(ac, ad) + glm::dot(ac, ac) * glm::cross(ad, ab) +
                        glm::dot(ad, ad) * glm::cross(ab, ac)) /
                       (2.0 * det);
  out = {a + offset, glm::dot(offset, offset)};
  return true;
}

// The smallest ball containing up to four points, by trying every ball that two, three or four of
// them define. Used only for a degenerate support set (collinear three, coplanar four), where no
// ball has them all on its boundary; in exact arithmetic Welzl's recursion never builds one, in
// floating point it can, and the smallest ball containing them is then the continuous answer.
Ball smallestContaining(std::span<const DVec3> support, double tolerance) {
  Ball best;
  double bestRadiusSquared = std::numeric_limits<double>::infinity();
  auto consider = [&](const Ball& ball) {
    if (ball.radiusSquared < bestRadiusSquared && containsAll(ball, support, tolerance)) {
      best = ball;
      bestRadiusSquared = ball.radiusSquared;
    }
  };
  const std::size_t n = support.size();
  if (n == 1) return {support[0], 0.0};
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) consider(diametral(support[i], support[j]));
  Ball ball;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k)
        if (circumcircle(support[i], support[j], support[k], ball)) consider(ball);
  if (n == 4 && circumsphere(support[0], support[1], support[2], support[3], ball)) consider(ball);
  return best;
}

// The smallest ball with every support point on its boundary.
Ball ballThrough(std::span<const DVec3> support, double tolerance) {
  Ball ball;
  switch (support.size()) {
    case 0:
      return ball;
    case 1:
      return {support[0], 0.0};
    case 2:
      return diametral(support[0], support[1]);
    case 3:
      if (circumcircle(support[0], support[1], support[2], ball)) return ball;
      break;
    default:
      if (circumsphere(support[0], support[1], support[2], support[3], ball)) return ball;
      break;
  }
  return smallestContaining(support, tolerance);
}

class WelzlSolver {
 public:
  WelzlSolver(Array<DVec3> points, double tolerance) : points_(std::move(points)), tolerance_(tolerance) {
    for (std::uint32_t i = 0; i < points_.size(); ++i) order_.push_back(i);
  }

  Ball solve() { return moveToFront(order_.end(), 0); }

 private:
  // The smallest ball containing the points of order_ before `end` with support_[0..supportSize)
  // on its boundary (Welzl's mb(P, R)).
  Ball moveToFront(std::list<std::uint32_t>::iterator end, int supportSize) {
    Ball ball = ballThrough(std::span<const DVec3>(support_.data(), supportSize), tolerance_);
    if (supportSize == 4) return ball;
    for (auto it = order_.begin(); it != end;) {
      const auto current = it++;
      const DVec3& p = points_[*current];
      if (isInside(ball, p)) continue;
      support_[supportSize] = p;
      ball = moveToFront(current, supportSize + 1);
      // Move-to-front: this point defines the ball of a prefix, so test it early from now on.
      order_.splice(order_.begin(), order_, current);
    }
    return ball;
  }

  bool isInside(const Ball& ball, const DVec3& p) const {
    if (ball.radiusSquared < 0.0) return false;
    const double r = std::sqrt(ball.radiusSquared) + tolerance_;
    return glm::dot(p - ball.center, p - ball.center) <= r * r;
  }

  Array<DVec3> points_;
  std::list<std::uint32_t> order_;
  std::array<DVec3, 4> support_{};
  double tolerance_;
};

// Fisher-Yates with a fixed-seed 64-bit LCG (Knuth's MMIX constants): Welzl's expected linear time
// needs a random order, and our answer must not depend on the standard library's shuffle.
void deterministicShuffle(Array<DVec3>& points) {
  std::uint64_t state = 0x2545F4914F6CDD1Dull;
  for (std::size_t i = points.size(); i > 1; --i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const std::size_t j = static_cast<std::size_t>((state >> 33) % i);
    std::swap(points[i - 1], points[j]);
  }
}

}  // namespace

BoundingSphere minimalBoundingSphere(std::span<const Vec3> points) {
  if (!bounding::requireFinitePoints("minimal_bounding_sphere", points)) return {};
  Array<DVec3> work(points.begin(), points.end());
  double size = 0.0;
  for (const DVec3& p : work) size = std::max(size, glm::length(p - work.front()));
  deterministicShuffle(work);
  WelzlSolver solver(std::move(work), kRelativeTolerance * size);
  const Ball ball = solver.solve();

  // The stored sphere is float: round the centre, then measure the radius from it over every point
  // and round it up, so that containment holds for the sphere actually returned.
  BoundingSphere sphere;
  sphere.center = Vec3(ball.center);
  double radius = 0.0;
  const DVec3 center(sphere.center);
  for (const Vec3& p : points) radius = std::max(radius, glm::length(DVec3(p) - center));
  float stored = static_cast<float>(radius);
  if (double(stored) < radius) stored = std::nextafter(stored, std::numeric_limits<float>::infinity());
  sphere.radius = stored;
  return sphere;
}

}  // namespace collide
