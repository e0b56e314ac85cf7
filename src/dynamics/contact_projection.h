// PenetrationResponse::Project: the lecture's projection to the closest valid position (slides
// 10-11) as a positional constraint in the solver's position stage. After each substep's position
// update, a contact whose deepest point penetrates beyond the linear slop moves its two bodies apart
// along its normal by that excess, split by projectApart (src/response/penetration.h): the
// displacement that minimises the mass-weighted squared displacements, so that in a one-way contact
// only the movable body moves, by all of it. Bodies are translated, not turned (the lecture's
// projection is that of particles). The soft contact still does the rest: the projection only
// removes what it leaves beyond the slop (a fast impact, a heavy body on a light one), at once
// instead of at the push-out speed.
#pragma once

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "dynamics/solver_body.h"

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

class ContactProjection {
 public:
  // The step's solved contacts, their points as anchors from the centres of mass at the step's start
  // (what the contact solver measures separations from).
  void prepare(std::span<const Contact> contacts, std::span<const std::uint32_t> solvedContacts,
               const Array<std::int32_t>& solverOf, const Array<SolverBodyInfo>& infos,
               const BodyStorage& storage);
  // One pass over the contacts, each projected with the bodies' displacements so far (Gauss-Seidel).
  void project(Array<SolverBody>& bodies, float linearSlop) const;

  std::size_t memoryBytes() const;  // World::memoryUse

 private:
  struct Point {
    Vec3 anchorA{0.0f};
    Vec3 anchorB{0.0f};
    float baseSeparation = 0.0f;  // the separation at the step's start minus n . (anchorB - anchorA)
  };
  struct Constraint {
    std::int32_t bodyA = kNoSolverBody;  // solver bodies; kNoSolverBody: static
    std::int32_t bodyB = kNoSolverBody;
    float inverseMassA = 0.0f;  // 0 for static and kinematic bodies
    float inverseMassB = 0.0f;
    Vec3 normal{0.0f};  // from A to B, fixed over the step
    std::uint32_t firstPoint = 0;
    std::uint32_t pointCount = 0;
  };
  Array<Constraint> constraints_;
  Array<Point> points_;
};

}  // namespace collide::detail
