// libccd as a reference for penetration tests, fed with our support mappings (shared by the
// differential tests of the primitives and of the polyhedra).
#pragma once

#include <collide/math.h>

#include "narrowphase/convex_support.h"

namespace collide::test {

// The full shape's support (core plus radius), as libccd wants it.
inline Vec3 fullSupport(const detail::ConvexSupport& s, const Vec3& d) {
  Vec3 p = s.supportCore(d);
  if (s.radius > 0.0f) p += s.radius * glm::normalize(d);
  return p;
}

// How far B must move along unit u to leave A: the support of A - B along u.
inline float directionalDepth(const detail::ConvexSupport& a, const detail::ConvexSupport& b, const Vec3& u) {
  return glm::dot(fullSupport(a, u) - fullSupport(b, -u), u);
}

}  // namespace collide::test

#if defined(COLLIDE_HAVE_CCD)
#include <ccd/ccd.h>

namespace collide::test {

inline void ccdSupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto& s = *static_cast<const detail::ConvexSupport*>(object);
  const Vec3 p = fullSupport(s, Vec3(direction->v[0], direction->v[1], direction->v[2]));
  for (int i = 0; i < 3; ++i) out->v[i] = p[i];
}

inline void ccdCenter(const void* object, ccd_vec3_t* out) {
  const auto& s = *static_cast<const detail::ConvexSupport*>(object);
  for (int i = 0; i < 3; ++i) out->v[i] = s.position[i];
}

// libccd set up for our ConvexSupport objects, with tight tolerances.
inline ccd_t makeCcd() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccdSupport;
  ccd.support2 = ccdSupport;
  ccd.center1 = ccdCenter;
  ccd.center2 = ccdCenter;
  ccd.max_iterations = 1000;
  ccd.epa_tolerance = 1e-7;
  ccd.dist_tolerance = 1e-8;
  return ccd;
}

}  // namespace collide::test

#endif
