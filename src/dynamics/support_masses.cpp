// Support masses: levels from the ground, carried mass from the top down, the scales of the
// contacts where a heavier body rests on a lighter one (support_masses.h).
#include "dynamics/support_masses.h"
#include "memory/heap_bytes.h"

#include <algorithm>
#include <cmath>

namespace collide::detail {

namespace {

// A contact supports when its normal is within 60 degrees of up: a box on a slope steeper than that
// slides off rather than rests, and a side-by-side contact carries no weight.
constexpr float kSupportCosine = 0.5f;

// The centre of a manifold's points, where the bodies' speeds along its normal are measured.
Vec3 manifoldCentre(const Manifold& m) {
  Vec3 point(0.0f);
  for (int k = 0; k < m.count; ++k) point += m.points[k].midpoint();
  return point / float(m.count);
}

// A body's velocity along the contact's normal at `point`.
float speedAlongNormal(const Contact& c, const Vec3& point, std::uint32_t body, std::int32_t solverBody,
                       const Array<SolverBody>& bodies, const BodyStorage& storage) {
  const SolverBody& b = bodies[solverBody];
  const Vec3 velocity =
      b.linearVelocity + glm::cross(b.angularVelocity, point - storage.states[body].centerOfMass);
  return glm::dot(velocity, c.manifold.normal);
}

}  // namespace

void SupportMasses::compute(std::span<const Contact> contacts, std::span<const std::uint32_t> solvedContacts,
                            const Array<std::int32_t>& solverOf, const Array<SolverBodyInfo>& infos,
                            const Array<SolverBody>& bodies, const BodyStorage& storage, const Vec3& gravity,
                            float restingSpeed) {
  scaleA_.clear();
  scaleB_.clear();
  supports_.clear();
  const float g = glm::length(gravity);
  if (!(g > 0.0f) || !std::isfinite(g)) return;
  if (!findSupports(contacts, solvedContacts, solverOf, infos, gravity / -g)) return;
  assignLevels(infos.size());
  orderCarryingSupports(infos.size());
  carryMasses(infos);
  markHeavyOnLightStacks(infos);
  scaleRestingContacts(contacts, infos, bodies, storage, restingSpeed);
}

// The supporting contacts; true when one has a heavier body on a lighter one (else nothing to do).
bool SupportMasses::findSupports(std::span<const Contact> contacts,
                                 std::span<const std::uint32_t> solvedContacts,
                                 const Array<std::int32_t>& solverOf, const Array<SolverBodyInfo>& infos,
                                 const Vec3& up) {
  const auto isDynamic = [&](std::int32_t s) {
    return s != kNoSolverBody && infos[s].dynamic && infos[s].inverseMass > 0.0f;
  };
  bool heavierOnLighter = false;
  for (const std::uint32_t index : solvedContacts) {
    const Contact& c = contacts[index];
    const float rise = glm::dot(c.manifold.normal, up);
    if (std::abs(rise) < kSupportCosine) continue;
    const bool lowerIsA = rise > 0.0f;  // the normal points from A to B
    const std::int32_t lower = solverOf[lowerIsA ? c.bodyA : c.bodyB];
    const std::int32_t upper = solverOf[lowerIsA ? c.bodyB : c.bodyA];
    if (!isDynamic(upper)) continue;
    const bool dynamicLower = isDynamic(lower);
    heavierOnLighter =
        heavierOnLighter || (dynamicLower && infos[upper].inverseMass < infos[lower].inverseMass);
    supports_.push_back({dynamicLower ? lower : kNoSolverBody, upper, index, lowerIsA});
  }
  return heavierOnLighter;
}

// Levels, breadth first from the ground, over the edges leaving each dynamic lower body (CSR).
void SupportMasses::assignLevels(std::size_t bodyCount) {
  level_.assign(bodyCount, -1);
  edgeStart_.assign(bodyCount + 1, 0);
  for (const Support& s : supports_) {
    if (s.lower != kNoSolverBody) ++edgeStart_[s.lower + 1];
  }
  for (std::size_t i = 1; i <= bodyCount; ++i) edgeStart_[i] += edgeStart_[i - 1];
  edges_.resize(edgeStart_[bodyCount]);
  byLevel_.assign(edgeStart_.begin(), edgeStart_.end() - 1);  // the fill cursor, for now
  for (std::uint32_t i = 0; i < supports_.size(); ++i) {
    if (supports_[i].lower != kNoSolverBody) edges_[byLevel_[supports_[i].lower]++] = i;
  }
  queue_.clear();
  for (const Support& s : supports_) {
    if (s.lower == kNoSolverBody && level_[s.upper] < 0) {
      level_[s.upper] = 1;
      queue_.push_back(static_cast<std::uint32_t>(s.upper));
    }
  }
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const std::uint32_t body = queue_[head];
    for (std::uint32_t e = edgeStart_[body]; e < edgeStart_[body + 1]; ++e) {
      const std::int32_t upper = supports_[edges_[e]].upper;
      if (level_[upper] >= 0) continue;
      level_[upper] = level_[body] + 1;
      queue_.push_back(static_cast<std::uint32_t>(upper));
    }
  }
}

// The supports that carry weight down a level (the upper body on the ground through them), by the
// upper body's level, highest first (a stable counting sort), and how many each body rests on.
void SupportMasses::orderCarryingSupports(std::size_t bodyCount) {
  const auto levelOf = [&](std::int32_t s) { return s == kNoSolverBody ? 0 : level_[s]; };
  const auto carries = [&](const Support& s) {
    return level_[s.upper] > 0 && levelOf(s.lower) >= 0 && levelOf(s.lower) < level_[s.upper];
  };
  int maxLevel = 0;
  for (const std::uint32_t body : queue_) maxLevel = std::max(maxLevel, level_[body]);
  supporters_.assign(bodyCount, 0);
  Array<std::uint32_t>& start = edgeStart_;  // the CSR is no longer needed
  start.assign(static_cast<std::size_t>(maxLevel) + 2, 0);
  for (const Support& s : supports_) {
    if (!carries(s)) continue;
    ++supporters_[s.upper];
    ++start[maxLevel - level_[s.upper] + 1];
  }
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  byLevel_.resize(start.back());
  for (std::uint32_t i = 0; i < supports_.size(); ++i) {
    if (carries(supports_[i])) byLevel_[start[maxLevel - level_[supports_[i].upper]]++] = i;
  }
}

// Carried mass, from the top down: a body's support mass is its own plus an equal share of the
// support mass of each body resting on it. Uppers come before the bodies under them.
void SupportMasses::carryMasses(const Array<SolverBodyInfo>& infos) {
  supportMass_.assign(infos.size(), 0.0f);
  for (const std::uint32_t body : queue_) supportMass_[body] = 1.0f / infos[body].inverseMass;
  for (const std::uint32_t i : byLevel_) {
    const Support& s = supports_[i];
    if (s.lower != kNoSolverBody)
      supportMass_[s.lower] += supportMass_[s.upper] / float(supporters_[s.upper]);
  }
}

std::int32_t SupportMasses::stackRoot(std::int32_t body) {
  while (stackOf_[body] != body) body = stackOf_[body] = stackOf_[stackOf_[body]];
  return body;
}

// The stacks (bodies joined by carrying supports) that hold a heavier body on a lighter one.
void SupportMasses::markHeavyOnLightStacks(const Array<SolverBodyInfo>& infos) {
  const std::size_t bodyCount = infos.size();
  stackOf_.resize(bodyCount);
  for (std::size_t b = 0; b < bodyCount; ++b) stackOf_[b] = static_cast<std::int32_t>(b);
  for (const std::uint32_t i : byLevel_) {
    const Support& s = supports_[i];
    if (s.lower == kNoSolverBody) continue;
    const std::int32_t a = stackRoot(s.lower), b = stackRoot(s.upper);
    if (a != b) stackOf_[std::max(a, b)] = std::min(a, b);  // deterministic: the smaller index is the root
  }
  heavyOnLight_.assign(bodyCount, 0);
  for (const std::uint32_t i : byLevel_) {
    const Support& s = supports_[i];
    if (s.lower != kNoSolverBody && infos[s.upper].inverseMass < infos[s.lower].inverseMass)
      heavyOnLight_[stackRoot(s.upper)] = 1;
  }
}

// In those stacks, each body appears to the contacts that carry weight as heavy as its support
// mass, on both sides: its load's weight then reaches the ground as fast as a uniform stack's.
// Only a body at rest along the normal is scaled (no faster than the restitution threshold): one
// that falls onto the body under it, or rises into the one above, meets it with its true mass.
// Scaled, a falling body would hit as a lighter one and a rising one would lift its load without
// slowing, and either gains energy; at rest the scaling moves only what gravity added this step.
void SupportMasses::scaleRestingContacts(std::span<const Contact> contacts,
                                         const Array<SolverBodyInfo>& infos, const Array<SolverBody>& bodies,
                                         const BodyStorage& storage, float restingSpeed) {
  scaleA_.assign(contacts.size(), 1.0f);
  scaleB_.assign(contacts.size(), 1.0f);
  const auto scaleOf = [&](std::int32_t body) {
    return (1.0f / infos[body].inverseMass) / supportMass_[body];
  };
  const auto scaleIn = [&](const Contact& c, const Vec3& centre, std::uint32_t body,
                           std::int32_t solverBody) {
    const float speed = speedAlongNormal(c, centre, body, solverBody, bodies, storage);
    return std::abs(speed) <= restingSpeed ? scaleOf(solverBody) : 1.0f;
  };
  for (const std::uint32_t i : byLevel_) {
    const Support& s = supports_[i];
    if (!heavyOnLight_[stackRoot(s.upper)]) continue;
    const Contact& c = contacts[s.contact];
    const std::uint32_t upperBody = s.lowerIsA ? c.bodyB : c.bodyA;
    const std::uint32_t lowerBody = s.lowerIsA ? c.bodyA : c.bodyB;
    const Vec3 centre = manifoldCentre(c.manifold);
    (s.lowerIsA ? scaleB_ : scaleA_)[s.contact] = scaleIn(c, centre, upperBody, s.upper);
    if (s.lower != kNoSolverBody)
      (s.lowerIsA ? scaleA_ : scaleB_)[s.contact] = scaleIn(c, centre, lowerBody, s.lower);
  }
}

std::size_t SupportMasses::memoryBytes() const {
  return heapBytes(scaleA_) + heapBytes(scaleB_) + heapBytes(supports_) + heapBytes(level_) +
         heapBytes(supportMass_) + heapBytes(stackOf_) + heapBytes(heavyOnLight_) + heapBytes(supporters_) +
         heapBytes(edgeStart_) + heapBytes(edges_) + heapBytes(queue_) + heapBytes(byLevel_);
}

}  // namespace collide::detail
