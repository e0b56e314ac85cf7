// A brute-force signed distance of two convex shapes from their support functions alone, as an
// independent reference for GJK/EPA where libccd or FCL are themselves wrong.
//
// For convex A and B with h(u) = max over a in A, b in B of u·(a - b) (the support of A - B), the
// signed distance is -min over unit u of h(u): when they overlap, h(u) is how far B must move along u
// to leave A, and the penetration depth is the smallest such move; when apart, -h(u) is the gap of
// the separating planes normal to u, and the distance is the largest gap. Every evaluated h(u) is
// therefore a certified bound (an upper bound of the depth, a lower bound of the distance), whoever
// computed u; the search below only has to find a good u. It samples the sphere densely (a
// Fibonacci lattice) and polishes the best samples by a pattern search on the sphere with random
// tangent directions (robust at the kinks of polytope supports), in double precision.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "narrowphase/convex_support.h"

namespace collide::test {

struct SupportReference {
  double signedDistance = 0.0;    // -min h(u)
  Vec3 normal{0.0f, 1.0f, 0.0f};  // the minimising u, from A to B
};

// h(u) for the whole shapes (core plus radius), in double precision from the float supports.
inline double supportOfDifference(const detail::ConvexSupport& a, const detail::ConvexSupport& b,
                                  const glm::dvec3& u) {
  const Vec3 uf(u);
  const glm::dvec3 pa(a.supportCore(uf));
  const glm::dvec3 pb(b.supportCore(-uf));
  return glm::dot(pa - pb, u) + double(a.radius) + double(b.radius);
}

inline SupportReference bruteForceSignedDistance(const detail::ConvexSupport& a,
                                                 const detail::ConvexSupport& b, int samples = 1500,
                                                 int polished = 4) {
  struct Candidate {
    double h;
    glm::dvec3 u;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(samples);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < samples; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / samples;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const glm::dvec3 u(r * std::cos(golden * i), z, r * std::sin(golden * i));
    candidates.push_back({supportOfDifference(a, b, u), u});
  }
  std::partial_sort(candidates.begin(), candidates.begin() + polished, candidates.end(),
                    [](const Candidate& x, const Candidate& y) { return x.h < y.h; });
  std::mt19937 rng(99);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Candidate best = candidates[0];
  for (int c = 0; c < polished; ++c) {
    Candidate current = candidates[c];
    // Start at about the lattice spacing and shrink to far below float resolution.
    double step = 2.0 * std::sqrt(4.0 * M_PI / samples);
    int failures = 0;
    while (step > 1e-9) {
      bool improved = false;
      for (int k = 0; k < 12; ++k) {
        glm::dvec3 t(gauss(rng), gauss(rng), gauss(rng));
        t -= glm::dot(t, current.u) * current.u;
        const double length = glm::length(t);
        if (length < 1e-12) continue;
        const glm::dvec3 u = glm::normalize(current.u + (step / length) * t);
        const double h = supportOfDifference(a, b, u);
        if (h < current.h) {
          current = {h, u};
          improved = true;
        }
      }
      if (improved) {
        failures = 0;
      } else if (++failures >= 2) {
        step *= 0.5;
        failures = 0;
      }
    }
    if (current.h < best.h) best = current;
  }
  return {-best.h, Vec3(best.u)};
}

}  // namespace collide::test
