// A body as the response models see it at one contact: mass properties, velocities and centre of
// mass, all in world frame. The world fills one from its body storage, a response model updates the
// velocities, and the world writes them back. Shared by the impact and friction models.
#pragma once

#include <collide/math.h>

namespace collide::detail {

struct ImpactBody {
  float inverseMass = 0.0f;  // 0: static or kinematic (infinite mass), a one-way collision
  // World frame. Zero for a particle (it does not rotate; lecture, slide 34: rigid bodies made of
  // particles get their rotation as an emerging behaviour) and for an infinite mass.
  Mat3 inverseInertia{0.0f};
  Vec3 linearVelocity{0.0f};
  Vec3 angularVelocity{0.0f};  // ignored (kept as is) for a particle
  Vec3 centerOfMass{0.0f};     // world
};

bool hasInfiniteMass(const ImpactBody& body);
// Finite mass and a zero inverse inertia.
bool isParticle(const ImpactBody& body);

// Velocity of the body's material point at a world point: v + omega x (point - centre).
Vec3 velocityAt(const ImpactBody& body, const Vec3& point);

// Applies an impulse at a world point: linear velocity += impulse / m, angular velocity +=
// I^-1 (r x impulse). No effect on an infinite mass.
void applyImpulseAt(ImpactBody& body, const Vec3& impulse, const Vec3& point);

// The contact's "inverse effective mass" matrix K: applying +P to B and -P to A at the point changes
// the relative velocity vB(point) - vA(point) by K P. Symmetric positive semidefinite; positive
// definite unless both masses are infinite.
Mat3 contactInverseMassMatrix(const ImpactBody& a, const ImpactBody& b, const Vec3& point);

// Throw collide::Error naming the function (context), the problem and the value: a body needs
// finite values, a non-negative inverse mass, and a zero inverse inertia when its mass is infinite;
// a contact needs a finite point and a unit normal (within 1e-3).
bool validateImpactBody(const ImpactBody& body, const char* context, const char* name);
bool validateContact(const Vec3& point, const Vec3& normal, const char* context);

// Whether the impact and friction laws accept these bodies and contact, without throwing: what
// validateImpactBody and validateContact require, and, for two finite masses, inverse inertias that
// are zero (a particle) or invertible (the interpolated impact glues them into one body, whose
// inertia adds theirs). The
// step asks before it applies the laws, for a fault earlier in the step (an overflowing force) may
// have left a body non-finite; the fault guard freezes it at the step's end.
bool canApplyImpact(const ImpactBody& a, const ImpactBody& b, const Vec3& point, const Vec3& normal);

}  // namespace collide::detail
