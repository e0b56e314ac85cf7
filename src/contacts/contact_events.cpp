// Contact and sensor events and their buffers: the step's events stage (contact_events.h).
#include "contacts/contact_events.h"

#include "bodies/body_parts.h"
#include "memory/heap_bytes.h"

#include <algorithm>

namespace collide::detail {

namespace {

SensorEvent makeSensorEvent(const BodyStorage& bodies, const Contact& contact, SensorEvent::Type type) {
  const bool aIsSensor = partIsSensor(bodies.records[contact.bodyA], contact.partA);
  return {type, bodies.idOf(aIsSensor ? contact.bodyA : contact.bodyB),
          bodies.idOf(aIsSensor ? contact.bodyB : contact.bodyA), aIsSensor ? contact.partA : contact.partB,
          aIsSensor ? contact.partB : contact.partA};
}

}  // namespace

void StepEvents::beginStep() {
  contacts.assign(pendingContacts.begin(), pendingContacts.end());
  contactOfEvent.assign(pendingContacts.size(), kNoContact);
  sensors.assign(pendingSensors.begin(), pendingSensors.end());
  pendingContacts.clear();
  pendingSensors.clear();
  faults.clear();
  jointBreaks.clear();
}

void StepEvents::endVanished(const BodyStorage& bodies, const Contact& old) {
  // Contacts of destroyed bodies were erased; a generation mismatch means the slot was reused.
  if (!old.touching || !bodies.records[old.bodyA].alive || !bodies.records[old.bodyB].alive) return;
  if (bodies.records[old.bodyA].generation != old.generationA ||
      bodies.records[old.bodyB].generation != old.generationB)
    return;
  if (old.sensor) {
    sensors.push_back(makeSensorEvent(bodies, old, SensorEvent::Type::End));
  } else {
    contacts.push_back(makeContactEvent(bodies, old, ContactEvent::Type::End));
    contactOfEvent.push_back(kNoContact);
  }
}

void StepEvents::endWithDestroyedBody(const BodyStorage& bodies, const Contact& contact) {
  if (!contact.touching) return;
  if (contact.sensor) {
    pendingSensors.push_back(makeSensorEvent(bodies, contact, SensorEvent::Type::End));
  } else {
    pendingContacts.push_back(makeContactEvent(bodies, contact, ContactEvent::Type::End));
  }
}

ContactEvent makeContactEvent(const BodyStorage& bodies, const Contact& c, ContactEvent::Type type) {
  ContactEvent e;
  e.type = type;
  e.a = bodies.idOf(c.bodyA);
  e.b = bodies.idOf(c.bodyB);
  e.partA = c.partA;
  e.partB = c.partB;
  e.normal = c.manifold.normal;
  int deepest = 0;
  for (int i = 0; i < c.manifold.count; ++i) {
    if (c.manifold.points[i].depth > c.manifold.points[deepest].depth) deepest = i;
    e.impulse += c.points[i].totalNormalImpulse;
    e.speed = std::max(e.speed, -c.points[i].relativeVelocity);
  }
  e.impulse += c.impactImpulse;
  e.speed = std::max(e.speed, c.impactSpeed);
  if (c.manifold.count > 0) e.point = c.manifold.points[deepest].midpoint();
  if (type == ContactEvent::Type::End) e.impulse = 0.0f;
  return e;
}

ContactData makeContactData(const BodyStorage& bodies, const Contact& c) {
  ContactData d;
  d.a = bodies.idOf(c.bodyA);
  d.b = bodies.idOf(c.bodyB);
  d.partA = c.partA;
  d.partB = c.partB;
  d.manifold = c.manifold;
  for (int i = 0; i < c.manifold.count; ++i) d.normalImpulses[i] = c.points[i].totalNormalImpulse;
  d.frictionImpulse = c.frictionImpulse;
  d.impactImpulse = c.impactImpulse;
  return d;
}

std::size_t emitContactEvents(const BodyStorage& bodies, Array<Contact>& contacts, StepEvents& events,
                              bool persistEvents) {
  std::size_t touchingCount = 0;
  const auto emit = [&](const Contact& c, ContactEvent::Type type) {
    events.contacts.push_back(makeContactEvent(bodies, c, type));
    events.contactOfEvent.push_back(static_cast<std::uint32_t>(&c - contacts.data()));
  };
  for (Contact& c : contacts) {
    // A speculative contact that stopped the bodies this step (the solver pushed, or the impact
    // stage gave an impulse) touched them, though it was still apart before: count it, so the begin
    // event carries the impact speed and impulse.
    if (!c.sensor && c.enabled && !c.touching) {
      c.touching = c.impactImpulse > 0.0f;
      for (int i = 0; i < c.manifold.count; ++i)
        c.touching = c.touching || c.points[i].maxNormalImpulse > 0.0f;
    }
    if (c.sensor) {
      if (c.touching != c.wasTouching) {
        const auto type = c.touching ? SensorEvent::Type::Begin : SensorEvent::Type::End;
        events.sensors.push_back(makeSensorEvent(bodies, c, type));
      }
      continue;
    }
    if (c.touching) ++touchingCount;
    if (c.touching && !c.wasTouching) emit(c, ContactEvent::Type::Begin);
    if (c.touching && c.wasTouching && persistEvents && !c.asleep) emit(c, ContactEvent::Type::Persist);
    if (!c.touching && c.wasTouching) emit(c, ContactEvent::Type::End);
  }
  return touchingCount;
}

void tellContactListener(const StepEvents& events, const BodyStorage& bodies, const Array<Contact>& contacts,
                         ContactListener& listener) {
  for (std::size_t i = 0; i < events.contacts.size(); ++i) {
    const ContactEvent& event = events.contacts[i];
    const std::uint32_t contact = events.contactOfEvent[i];
    if (event.type == ContactEvent::Type::End || contact == StepEvents::kNoContact) {
      listener.onEnd(event);
    } else if (event.type == ContactEvent::Type::Begin) {
      listener.onBegin(makeContactData(bodies, contacts[contact]));
    } else {
      listener.onPersist(makeContactData(bodies, contacts[contact]));
    }
  }
}

std::size_t StepEvents::memoryBytes() const {
  return heapBytes(contacts) + heapBytes(contactOfEvent) + heapBytes(sensors) + heapBytes(faults) +
         heapBytes(jointBreaks) + heapBytes(pendingContacts) + heapBytes(pendingSensors);
}

}  // namespace collide::detail
