// The soft-step contact solver (Catto, "Solver2D" blog posts, 2024; Box2D v3's contact_solver.c),
// written for 3D. Per step: prepare once (anchors, effective masses, the relative normal velocity
// before the solve); per substep: warm start, solve with the soft position bias, integrate
// positions, relax without the bias; at the end: restitution from the stored approach velocity.
#pragma once

#include "contacts/contact_cache.h"
#include "dynamics/body_storage.h"

#include <collide/world.h>

#include <vector>

namespace collide::detail {

// A soft constraint as a mass-spring-damper at substep h (Catto, GDC 2011 "Soft Constraints").
struct Softness {
  float biasRate = 0.0f;
  float massScale = 1.0f;
  float impulseScale = 0.0f;
};
Softness makeSoftness(float hertz, float dampingRatio, float h);

struct ConstraintPoint {
  Vec3 anchorA{0.0f};  // from A's centre of mass to the contact point, world, at the step start
  Vec3 anchorB{0.0f};
  float adjustedSeparation = 0.0f;  // separation minus dot(anchorB - anchorA, normal)
  float normalMass = 0.0f;
  std::array<float, 2> tangentMass{0.0f, 0.0f};
};

struct ContactConstraint {
  std::uint32_t contactIndex = 0;
  std::uint32_t bodyA = 0;
  std::uint32_t bodyB = 0;
  Vec3 normal{0.0f};
  std::array<Vec3, 2> tangents{Vec3(0.0f), Vec3(0.0f)};
  float friction = 0.0f;
  float restitution = 0.0f;
  Softness softness;
  int pointCount = 0;
  std::array<ConstraintPoint, Manifold::kMaxPoints> points{};
};

struct SolverSettings {
  Vec3 gravity{0.0f};
  int substeps = 6;
  ContactTuning tuning;
  bool friction = true;
};

// The pieces of the soft step; the substep loop that calls them (with the joints in between) is
// World::Impl::solve in src/world.cpp.
// Once per step: the constraints of the enabled, awake, non-sensor contacts with points (the vector
// is reused across steps: no allocation after warm-up), with the approach velocity before the solve.
void prepareContacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                     std::vector<ContactConstraint>& constraints, const SolverSettings& settings, float h);
// Per substep: apply last substep's accumulated impulses.
void warmStartContacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                       const std::vector<ContactConstraint>& constraints);
// Per substep: one pass over the contacts; useBias = false is the relax pass. Impulses are written
// back into the contacts' point states for warm starting and events.
void solveContacts(BodyStorage& bodies, std::vector<Contact>& contacts,
                   const std::vector<ContactConstraint>& constraints, float h, float pushOutSpeed,
                   bool useBias);
// Once at the end: Newton's restitution from the approach velocity stored by prepareContacts.
void applyRestitution(BodyStorage& bodies, std::vector<Contact>& contacts,
                      const std::vector<ContactConstraint>& constraints, float threshold);

}  // namespace collide::detail
