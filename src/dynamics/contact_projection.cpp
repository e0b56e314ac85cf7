// The lecture's projection in the solver's position stage, PenetrationResponse::Project
// (contact_projection.h).
#include "dynamics/contact_projection.h"

#include "memory/heap_bytes.h"
#include "response/penetration.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

void ContactProjection::prepare(std::span<const Contact> contacts,
                                std::span<const std::uint32_t> solvedContacts,
                                const Array<std::int32_t>& solverOf, const Array<SolverBodyInfo>& infos,
                                const BodyStorage& storage) {
  constraints_.clear();
  points_.clear();
  const auto inverseMass = [&](std::int32_t solverBody) {
    return solverBody != kNoSolverBody && infos[solverBody].dynamic ? infos[solverBody].inverseMass : 0.0f;
  };
  for (const std::uint32_t index : solvedContacts) {
    const Contact& c = contacts[index];
    Constraint constraint;
    constraint.bodyA = solverOf[c.bodyA];
    constraint.bodyB = solverOf[c.bodyB];
    constraint.inverseMassA = inverseMass(constraint.bodyA);
    constraint.inverseMassB = inverseMass(constraint.bodyB);
    if (constraint.inverseMassA == 0.0f && constraint.inverseMassB == 0.0f) continue;
    constraint.normal = c.manifold.normal;
    constraint.firstPoint = static_cast<std::uint32_t>(points_.size());
    constraint.pointCount = static_cast<std::uint32_t>(c.manifold.count);
    const Vec3 centerA = storage.states[c.bodyA].centerOfMass0;
    const Vec3 centerB = storage.states[c.bodyB].centerOfMass0;
    for (int k = 0; k < c.manifold.count; ++k) {
      const ContactPoint& p = c.manifold.points[k];
      Point point;
      point.anchorA = p.midpoint() - centerA;
      point.anchorB = p.midpoint() - centerB;
      point.baseSeparation = -p.depth - glm::dot(point.anchorB - point.anchorA, constraint.normal);
      points_.push_back(point);
    }
    constraints_.push_back(constraint);
  }
}

void ContactProjection::project(Array<SolverBody>& bodies, float linearSlop) const {
  static const SolverBody kStill;  // a static body: not moved, not turned
  for (const Constraint& c : constraints_) {
    const SolverBody& a = c.bodyA != kNoSolverBody ? bodies[c.bodyA] : kStill;
    const SolverBody& b = c.bodyB != kNoSolverBody ? bodies[c.bodyB] : kStill;
    // The current separation of each point from the bodies' change of pose since the step began.
    float deepest = 0.0f;
    for (std::uint32_t k = 0; k < c.pointCount; ++k) {
      const Point& p = points_[c.firstPoint + k];
      const Vec3 moved =
          (b.deltaPosition + b.deltaRotation * p.anchorB) - (a.deltaPosition + a.deltaRotation * p.anchorA);
      deepest = std::max(deepest, -(glm::dot(moved, c.normal) + p.baseSeparation));
    }
    // A non-finite depth (a body the fault guard is about to stop) is left alone.
    if (!(deepest > linearSlop) || !std::isfinite(deepest)) continue;
    const Displacements d =
        projectApartUnchecked(c.inverseMassA, c.inverseMassB, c.normal, deepest - linearSlop);
    if (c.bodyA != kNoSolverBody) bodies[c.bodyA].deltaPosition += d.a;
    if (c.bodyB != kNoSolverBody) bodies[c.bodyB].deltaPosition += d.b;
  }
}

std::size_t ContactProjection::memoryBytes() const { return heapBytes(constraints_) + heapBytes(points_); }

}  // namespace collide::detail
