// Sensors a body crossed within one step, found by sweeping the pair (sensor_crossings.h).
#include "contacts/sensor_crossings.h"

#include <collide/narrowphase.h>

namespace collide::detail {

namespace {

bool moved(const BodyState& s) { return s.centerOfMass != s.centerOfMass0 || s.rotation != s.rotation0; }

}  // namespace

void reportSensorCrossings(const BodyStorage& bodies, const BroadPhase& broadPhase,
                           std::span<const ProxyPair> pairs, std::span<const Contact> contacts,
                           const PairFilters& filters, StepEvents& events) {
  ToiSettings touch;
  touch.targetSeparation = 0.0f;
  touch.tolerance = 1e-4f;
  for (const ProxyPair& pair : pairs) {
    const auto ia = static_cast<std::uint32_t>(broadPhase.userValue(pair.a));
    const auto ib = static_cast<std::uint32_t>(broadPhase.userValue(pair.b));
    const BodyRecord& ra = bodies.records[ia];
    const BodyRecord& rb = bodies.records[ib];
    if (ra.sensor == rb.sensor || !ra.alive || !rb.alive) continue;  // exactly one sensor
    if (!pairAllowed(bodies, filters, ia, ib)) continue;
    const BodyState& sa = bodies.states[ia];
    const BodyState& sb = bodies.states[ib];
    if (!moved(sa) && !moved(sb)) continue;
    const Contact* contact = findContact(contacts, pairKey(pair.a.index, pair.b.index));
    if (contact && contact->touching) continue;  // inside at the start: its own events
    const Sweep sweepA = bodySweep(ra, sa);
    const Sweep sweepB = bodySweep(rb, sb);
    if (!timeOfImpact(ra.shape, sweepA, rb.shape, sweepB, touch).hit()) continue;
    Manifold atEnd;
    if (collide::collide(ra.shape, sweepA.at(1.0f), rb.shape, sweepB.at(1.0f), atEnd) &&
        atEnd.maxDepth() >= 0.0f)
      continue;  // inside at the end: the next step's contact begins the overlap
    const BodyId sensor = bodies.idOf(ra.sensor ? ia : ib);
    const BodyId visitor = bodies.idOf(ra.sensor ? ib : ia);
    events.sensors.push_back({SensorEvent::Type::Begin, sensor, visitor});
    events.sensors.push_back({SensorEvent::Type::End, sensor, visitor});
  }
}

}  // namespace collide::detail
