#include "contacts/contact_cache.h"

namespace collide::detail {

void matchContactPoints(const Contact& previous, Contact& current) {
  std::array<bool, Manifold::kMaxPoints> taken{};
  for (int i = 0; i < current.manifold.count; ++i) {
    const ContactPoint& point = current.manifold.points[i];
    int best = -1;
    float bestDistance2 = 0.0f;
    for (int j = 0; j < previous.manifold.count; ++j) {
      if (taken[j] || previous.manifold.points[j].featureId != point.featureId) continue;
      // Several old points may share an id (generic GJK contacts all use 0): the nearest wins.
      const Vec3 d = previous.manifold.points[j].midpoint() - point.midpoint();
      const float distance2 = glm::dot(d, d);
      if (best < 0 || distance2 < bestDistance2) {
        best = j;
        bestDistance2 = distance2;
      }
    }
    ContactPointState& state = current.points[i];
    state = ContactPointState{};
    if (best >= 0) {
      taken[best] = true;
      state.normalImpulse = previous.points[best].normalImpulse;
      state.tangentImpulse = previous.points[best].tangentImpulse;
      state.prolonged = true;
    }
  }
}

}  // namespace collide::detail
