// Oriented bounding box fitting. The box is chosen among candidates built on the convex hull: for a
// direction n, the tightest box with one axis along n is the minimum-area rectangle of the hull
// projected across n (rotating calipers, Freeman & Shapira 1975) times the hull's extent along n.
// Directions tried: every hull face normal (a box face flush with a hull face is the common optimum;
// O'Rourke 1985 showed that the true optimum has two adjacent faces each flush with a hull edge), the
// principal axes of the points (Gottschalk et al., OBBTree 1996) and the coordinate axes, which make
// the result never larger than the axis-aligned box.
//
// That search costs (faces x vertices) and a hull of many vertices (a scanned asset, a finely
// tessellated sphere) has as many faces: past kExactHullVertices the directions come from a coarse
// hull instead, made of the hull's extreme vertices along kCoarseDirections fixed directions, as
// DiTO does (Larsson & Kallberg 2011, "Fast Computation of Tight-Fitting Oriented Bounding Boxes").
// Its best frames, the principal axes' and the coordinate axes' are then measured over every hull
// vertex, so the box stays no larger than the axis-aligned box or the principal axes' box, and the
// final extents are measured over every point as before.
#include <collide/bounding.h>

#include "base/fail.h"
#include "bounding/min_area_rectangle.h"
#include "bounding/obb_fit.h"
#include "bounding/point_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace collide {

namespace {

using DVec3 = glm::dvec3;
using bounding::basisAcross;

struct Candidate {
  glm::dmat3 axes{1.0};  // columns: box axes, right-handed
  double volume = std::numeric_limits<double>::infinity();
};

constexpr std::size_t kExactHullVertices = 1024;
constexpr int kCoarseDirections = 256;
constexpr std::size_t kFinalists = 8;

// The tightest box with one axis along the unit direction n, over the hull vertices.
Candidate boxAlong(const DVec3& n, std::span<const DVec3> vertices) {
  DVec3 u, v;
  basisAcross(n, u, v);
  Array<glm::dvec2> projected;
  projected.reserve(vertices.size());
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const DVec3& p : vertices) {
    projected.emplace_back(glm::dot(u, p), glm::dot(v, p));
    const double h = glm::dot(n, p);
    low = std::min(low, h);
    high = std::max(high, h);
  }
  const Array<glm::dvec2> hull = bounding::convexHull2d(std::move(projected));
  const bounding::Rectangle2d rectangle = bounding::minimumAreaRectangle(hull);
  Candidate candidate;
  const DVec3 first = rectangle.axis.x * u + rectangle.axis.y * v;
  const DVec3 second = glm::cross(n, first);  // the rectangle's left perpendicular, in 3D
  candidate.axes = glm::dmat3(first, second, n);
  candidate.volume = rectangle.area() * (high - low);
  return candidate;
}

// Every hull face normal, the principal axes and the coordinate axes, each over every hull vertex.
Candidate bestOverFaces(const ConvexHull& hull, std::span<const DVec3> vertices,
                        const bounding::PrincipalAxes& pca) {
  Array<DVec3> directions;
  for (const ConvexHull::Face& face : hull.faces())
    directions.push_back(glm::normalize(DVec3(face.plane.normal)));
  for (int i = 0; i < 3; ++i) directions.push_back(pca.axes[i]);
  for (int i = 0; i < 3; ++i) directions.push_back(glm::dmat3(1.0)[i]);
  Candidate best;
  for (const DVec3& n : directions) {
    const Candidate candidate = boxAlong(n, vertices);
    if (candidate.volume < best.volume) best = candidate;
  }
  return best;
}

// The volume of the box with these axes around the vertices: the product of their extents.
double volumeAlong(const glm::dmat3& axes, std::span<const DVec3> vertices) {
  DVec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (const DVec3& p : vertices) {
    const DVec3 local = glm::transpose(axes) * p;
    low = glm::min(low, local);
    high = glm::max(high, local);
  }
  const DVec3 size = high - low;
  return size.x * size.y * size.z;
}

// The faces of the coarse hull give candidate frames; the best few, the principal axes and the
// coordinate axes are measured over every hull vertex.
Candidate bestOverCoarseHull(std::span<const DVec3> vertices, const bounding::PrincipalAxes& pca) {
  Array<Vec3> extremes;
  for (const std::size_t k : bounding::extremeIndices(vertices, kCoarseDirections))
    extremes.push_back(Vec3(vertices[k]));
  const ConvexHull coarse = ConvexHull::fromPoints(extremes);
  const Array<DVec3> coarseVertices(coarse.vertices().begin(), coarse.vertices().end());
  Array<Candidate> finalists;
  for (const ConvexHull::Face& face : coarse.faces())
    finalists.push_back(boxAlong(glm::normalize(DVec3(face.plane.normal)), coarseVertices));
  const auto byVolume = [](const Candidate& a, const Candidate& b) { return a.volume < b.volume; };
  const std::size_t kept = std::min(kFinalists, finalists.size());
  std::partial_sort(finalists.begin(), finalists.begin() + kept, finalists.end(), byVolume);
  finalists.resize(kept);
  finalists.push_back(Candidate{pca.axes});
  finalists.push_back(Candidate{glm::dmat3(1.0)});
  Candidate best;
  for (Candidate& candidate : finalists) {
    candidate.volume = volumeAlong(candidate.axes, vertices);
    if (candidate.volume < best.volume) best = candidate;
  }
  return best;
}

}  // namespace

OrientedBox fitOrientedBox(std::span<const Vec3> points) {
  const detail::ErrorScope scope;
  if (!bounding::requireFinitePoints("fit_oriented_box", points)) return {};
  const ConvexHull hull = detail::withErrorContext(
      "fit_oriented_box: an oriented box needs points that span a volume (",
      [&] { return ConvexHull::fromPoints(points); }, ")");
  COLLIDE_RETURN_IF_FAILED({});
  return bounding::fitOrientedBoxOnHull(points, hull);
}

OrientedBox bounding::fitOrientedBoxOnHull(std::span<const Vec3> points, const ConvexHull& hull) {
  Array<DVec3> vertices(hull.vertices().begin(), hull.vertices().end());
  // Centre the vertices so that projections of a cloud far from the origin keep their precision.
  DVec3 origin(0.0);
  for (const DVec3& p : vertices) origin += p;
  origin /= double(vertices.size());
  for (DVec3& p : vertices) p -= origin;

  const bounding::PrincipalAxes pca = bounding::principalAxes(points);
  const Candidate best = vertices.size() <= kExactHullVertices ? bestOverFaces(hull, vertices, pca)
                                                               : bestOverCoarseHull(vertices, pca);

  // Store the rotation as a float quaternion, then measure the extents along the axes that
  // quaternion really has, over every input point: the returned box contains them all even though
  // the rotation was rounded (and Qhull's merged faces may leave a point a hair outside its hull).
  OrientedBox box;
  box.transform.rotation = bounding::rotationFromAxes(best.axes);
  const glm::dmat3 axes = glm::dmat3(glm::mat3_cast(box.transform.rotation));
  DVec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (const Vec3& p : points) {
    const DVec3 local = glm::transpose(axes) * (DVec3(p) - origin);
    low = glm::min(low, local);
    high = glm::max(high, local);
  }
  box.transform.position = Vec3(origin + axes * (0.5 * (low + high)));
  // The centre was rounded to float too: the half extents are measured from the stored centre and
  // rounded up.
  DVec3 reach(0.0);
  for (const Vec3& p : points)
    reach = glm::max(reach, glm::abs(glm::transpose(axes) * (DVec3(p) - DVec3(box.transform.position))));
  for (int i = 0; i < 3; ++i) {
    float h = static_cast<float>(reach[i]);
    if (double(h) < reach[i]) h = std::nextafter(h, std::numeric_limits<float>::infinity());
    box.box.halfExtents[i] = h;
  }
  return box;
}

}  // namespace collide
