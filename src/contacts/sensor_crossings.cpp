// Sensors a body crossed within one step, found by sweeping the pair (sensor_crossings.h).
#include "contacts/sensor_crossings.h"

#include <collide/narrowphase.h>

#include "bodies/body_parts.h"

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
    if (!ra.alive || !rb.alive) continue;
    const bool parts = hasParts(ra) || hasParts(rb);
    if (!parts && ra.sensor == rb.sensor) continue;  // exactly one sensor
    if (!pairAllowed(bodies, filters, ia, ib)) continue;
    const BodyState& sa = bodies.states[ia];
    const BodyState& sb = bodies.states[ib];
    if (!moved(sa) && !moved(sb)) continue;
    const std::uint64_t key = pairKey(pair.a.index, pair.b.index);
    const Sweep sweepA = bodySweep(ra, sa);
    const Sweep sweepB = bodySweep(rb, sb);
    forEachAllowedPartPair(ra, rb, [&](std::uint32_t partA, std::uint32_t partB) {
      const bool sensorA = partIsSensor(ra, partA);
      if (sensorA == partIsSensor(rb, partB)) return;  // exactly one sensor part
      const Contact* contact = findContact(contacts, key, partA, partB);
      if (contact && contact->touching) return;  // inside at the start: its own events
      const Shape& shapeA = partShape(ra, partA);
      const Shape& shapeB = partShape(rb, partB);
      const Sweep partSweepA = partSweep(sweepA, partLocalPose(ra, partA));
      const Sweep partSweepB = partSweep(sweepB, partLocalPose(rb, partB));
      // A part near float's limit from its body's centre: no sweep float can hold (as in the
      // continuous pass).
      if (!sweepStaysFinite(partSweepA) || !sweepStaysFinite(partSweepB)) return;
      if (!timeOfImpact(shapeA, partSweepA, shapeB, partSweepB, touch).hit()) return;
      Manifold atEnd;
      if (collide::collide(shapeA, partSweepA.at(1.0f), shapeB, partSweepB.at(1.0f), atEnd) &&
          atEnd.maxDepth() >= 0.0f)
        return;  // inside at the end: the next step's contact begins the overlap
      const BodyId sensor = bodies.idOf(sensorA ? ia : ib);
      const BodyId visitor = bodies.idOf(sensorA ? ib : ia);
      const std::uint32_t sensorPart = sensorA ? partA : partB;
      const std::uint32_t visitorPart = sensorA ? partB : partA;
      events.sensors.push_back({SensorEvent::Type::Begin, sensor, visitor, sensorPart, visitorPart});
      events.sensors.push_back({SensorEvent::Type::End, sensor, visitor, sensorPart, visitorPart});
    });
  }
}

}  // namespace collide::detail
