// Impacts by impulses (lecture, slides 13-34), the stage before the solve: a contact whose bodies
// meet this step faster than the restitution threshold gets an impulse that resolves the impact at
// once — restitution on the normal relative velocity with Coulomb friction for ImpactModel::Newton
// (contacts with a bounciness above 0; an inelastic impact is the solver's), the lecture's
// interpolated impact for ImpactModel::Interpolated. The impulse changes the bodies' velocities, and
// every contact of those bodies is looked at again, so that an impact travels through bodies at rest
// against each other as the lecture's pairwise law has it: a ball hitting the end of a row of touching
// balls stops, and the ball at the far end leaves (Newton's cradle). Several contacts hit at once
// each get their own impulse, so an elastic impact in a corner keeps the energy too.
//
// A contact meets this step when it touches or its gap closes within the step at the approach
// speed it has when its turn comes (an impact elsewhere may set a resting or separating contact
// approaching, and it then gets its own impact, not the solver's inelastic stop); its impulse acts at the
// average of its deepest points (within the linear slop). The impacts are resolved in contact order, then in
// the order their bodies were hit, at most kImpactVisits per contact, so a body squeezed between two bouncing
// walls ends the stage.
#pragma once

#include <collide/settings.h>

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"

#include <cstdint>
#include <vector>

namespace collide::detail {

inline constexpr int kImpactVisits = 8;

class ImpactStage {
 public:
  void run(BodyStorage& bodies, Array<Contact>& contacts, ImpactModel model, const ContactTuning& tuning,
           const Vec3& gravity, float dt);
  // After the solve: each body hit this step moved back by its velocity change times the time of
  // its impact (see resolve), once the step's integration has moved it.
  void applyTimeShifts(BodyStorage& bodies);

  std::size_t memoryBytes() const;  // World::memoryUse

 private:
  struct Entry {
    std::uint32_t contact = 0;
    Vec3 point{0.0f};
    bool queued = false;
    int visits = 0;
  };
  void collect(const BodyStorage& bodies, const Array<Contact>& contacts, ImpactModel model,
               const ContactTuning& tuning, float dt);
  void linkBodies(const Array<Contact>& contacts, std::size_t bodyCount);
  bool resolve(BodyStorage& bodies, Contact& contact, const Entry& entry, ImpactModel model,
               const ContactTuning& tuning, const Vec3& gravity, float dt);
  void enqueueContactsOf(std::uint32_t body);

  Array<Entry> entries_;
  Array<std::uint32_t> queue_;
  // The entries of body b are entryOfBody_[firstOfBody_[b], firstOfBody_[b + 1]).
  Array<std::uint32_t> firstOfBody_;
  Array<std::uint32_t> entryOfBody_;
  Array<float> impactTime_;  // per body: when in the step its last impact happened
  Array<Vec3> linearShift_;  // per body: the motion to take back after the step
  Array<Vec3> angularShift_;
  bool shifted_ = false;
};

}  // namespace collide::detail
