// The last stage of the step that gameplay code sees: contact and sensor events (lecture: ad-hoc
// effects through events), and the buffers they are handed out from. A contact begins when it starts
// touching, persists while it goes on touching (only when asked: a resting pile would report every
// contact every step), and ends when it stops touching or its pair vanishes.
#pragma once

#include <collide/events.h>

#include "bodies/body_storage.h"
#include "contacts/contact_cache.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace collide::detail {

// The events of the last step, in a deterministic order (the contacts' pair order), and the end
// events of contacts whose body was destroyed between steps, handed out first with the next step's.
struct StepEvents {
  Array<ContactEvent> contacts;
  // For each contact event, its contact's index in the step's contact array (the contact listener
  // reads the manifold there), or kNoContact for the end of a vanished pair.
  static constexpr std::uint32_t kNoContact = 0xFFFFFFFFu;
  Array<std::uint32_t> contactOfEvent;
  Array<SensorEvent> sensors;
  Array<FaultEvent> faults;
  Array<JointBreakEvent> jointBreaks;
  Array<ContactEvent> pendingContacts;
  Array<SensorEvent> pendingSensors;

  // The lists start over, with the pending end events first.
  void beginStep();
  // A touching contact that ended because its pair is gone (no longer kept by the broad phase or
  // filtered out): its end event now. Nothing for contacts whose body slot was freed or reused.
  void endVanished(const BodyStorage& bodies, const Contact& contact);
  // A touching contact of a body being destroyed: its end event with the next step's.
  void endWithDestroyedBody(const BodyStorage& bodies, const Contact& contact);

  std::size_t memoryBytes() const;  // World::memoryUse
};

ContactEvent makeContactEvent(const BodyStorage& bodies, const Contact& contact, ContactEvent::Type type);
// The whole contact, as World::visitContacts and the contact listener hand it out.
ContactData makeContactData(const BodyStorage& bodies, const Contact& contact);

// The stage: begin, persist (with persistEvents) and end events of every contact after the solve,
// and sensor begin and end events. Returns the number of touching (non-sensor) contacts.
std::size_t emitContactEvents(const BodyStorage& bodies, Array<Contact>& contacts, StepEvents& events,
                              bool persistEvents);

// The step's contact events told to the listener in their order, each begin and persist with the
// whole contact, after the step (a listener may then query the world).
void tellContactListener(const StepEvents& events, const BodyStorage& bodies, const Array<Contact>& contacts,
                         ContactListener& listener);

}  // namespace collide::detail
