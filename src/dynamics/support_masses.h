// Support masses: a heavy body resting on a light one, and a stack of any mass ratio, rest instead
// of sinking into themselves.
//
// Gauss-Seidel moves a velocity error across a contact in proportion to the masses on its two
// sides: a 1,000 kg box on a 1 kg one presses the light box into the ground for about a thousand
// passes before the ground's push reaches the heavy box, and a stack alternating 1 kg and 100 kg
// boxes sinks into itself. Where a body rests on a lighter one (the contact's normal within 60
// degrees of "up", against gravity), the whole stack it belongs to is solved with support masses:
// in every contact that carries weight down a level, each body's inverse mass and inertia are scaled
// so that it appears as heavy as itself plus everything it carries. A body then answers the push
// from above as its whole load would, and the ground's answer reaches the top in a few passes.
// Carried mass is shared equally among a body's supports, from the top of each stack down (levels
// counted from static or kinematic ground).
//
// Stacks of equal or downward-heavier bodies converge as they are and are solved as before. Only a
// body at rest along the contact's normal (within the restitution threshold) is scaled: a falling or
// rising one meets the other with its true mass (scaled, a falling body would hit as a lighter one
// and a rising one would lift its load without slowing, both adding energy). What it
// bends: in a scaled contact the impulses are equal and opposite but the velocity changes follow the
// support masses, so momentum along it is not conserved, and its normal impulse (and the friction
// bound) exceeds the true load (docs/architecture.md, "Mass ratios: support masses"). Erleben's
// "shock propagation by mass scaling" and PhysX's per-contact inverse mass scales are the models.
#pragma once

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"
#include "dynamics/solver_body.h"

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

class SupportMasses {
 public:
  // The scales for the step's solved contacts. None without gravity or where no body rests on a
  // lighter one (the common case costs one scan of the solved contacts).
  void compute(std::span<const Contact> contacts, std::span<const std::uint32_t> solvedContacts,
               const Array<std::int32_t>& solverOf, const Array<SolverBodyInfo>& infos,
               const Array<SolverBody>& bodies, const BodyStorage& storage, const Vec3& gravity,
               float restingSpeed);

  std::size_t memoryBytes() const;  // World::memoryUse

  void clear() {
    scaleA_.clear();
    scaleB_.clear();
  }
  bool empty() const { return scaleA_.empty(); }
  // The factors on body A's and body B's inverse mass and inertia in contact `index` (1: unscaled).
  float scaleA(std::uint32_t index) const { return scaleA_[index]; }
  float scaleB(std::uint32_t index) const { return scaleB_[index]; }

 private:
  struct Support {
    std::int32_t lower;  // kNoSolverBody: static or kinematic ground
    std::int32_t upper;  // a dynamic solver body
    std::uint32_t contact;
    bool lowerIsA;
  };
  // The stages of compute, in order.
  bool findSupports(std::span<const Contact> contacts, std::span<const std::uint32_t> solvedContacts,
                    const Array<std::int32_t>& solverOf, const Array<SolverBodyInfo>& infos, const Vec3& up);
  void assignLevels(std::size_t bodyCount);
  void orderCarryingSupports(std::size_t bodyCount);
  void carryMasses(const Array<SolverBodyInfo>& infos);
  void markHeavyOnLightStacks(const Array<SolverBodyInfo>& infos);
  void scaleRestingContacts(std::span<const Contact> contacts, const Array<SolverBodyInfo>& infos,
                            const Array<SolverBody>& bodies, const BodyStorage& storage, float restingSpeed);
  std::int32_t stackRoot(std::int32_t body);  // union-find with path halving

  Array<float> scaleA_, scaleB_;  // by contact index; empty when nothing is scaled
  // Scratch, kept between steps for its capacity.
  Array<Support> supports_;
  Array<std::int32_t> level_;
  Array<float> supportMass_;
  Array<std::int32_t> stackOf_;       // union-find over the carrying supports
  Array<std::uint8_t> heavyOnLight_;  // by stack root
  Array<std::uint32_t> supporters_, edgeStart_, edges_, queue_, byLevel_;
};

}  // namespace collide::detail
