// One step of the world: the lecture's pipeline, one stage a call, each in the folder of its layer.
//   proxies and bounds -> broad phase -> contacts (narrow phase, manifold reuse, pre-solve) ->
//   impacts -> solve (soft step) -> friction models and rolling resistance -> continuous -> revert ->
//   fault guard -> events -> islands and sleep.
// docs/architecture.md walks one body through these stages.
#include "world_impl.h"

#include "bodies/body_bounds.h"
#include "contacts/sensor_crossings.h"
#include "dynamics/continuous.h"
#include "dynamics/fault_guard.h"
#include "response/contact_response.h"
#include "response/revert.h"

#include <chrono>

namespace collide {

namespace {

detail::ContactUpdateSettings contactSettings(const WorldDef& def) {
  return {def.contact, def.frictionCombine, def.bouncinessCombine, def.impactModel};
}

detail::StepSettings solverSettings(const WorldDef& def) {
  detail::StepSettings settings;
  settings.gravity = def.gravity;
  settings.substeps = def.substeps;
  settings.relaxPasses = def.contact.relaxPasses;
  settings.tuning = def.contact;
  // Viscous and damping friction replace the solver's Coulomb friction (applied after the solve).
  settings.friction = def.frictionModel == FrictionModel::Coulomb;
  settings.projection = def.penetrationResponse == PenetrationResponse::Project;
  return settings;
}

// The wall time since the last lap, for the step's stage timings.
class StageClock {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

void World::Impl::step(float dt) {
  const ContactTuning& tuning = def.contact;
  StageClock clock;
  StageTimes time;
  events.beginStep();
  proxyUpdate.run(bodies, *broadPhase, dt, tuning.speculativeDistance, tasks);
  lastStats = StepStats(broadPhase->findPairs(pairs, tasks));
  if (def.sleeping) detail::wakeTouchedIslands(bodies, *broadPhase, pairs, tuning.speculativeDistance, dt);
  time.broadPhase = clock.lap();
  const detail::PairFilters filters{&jointedApart, &pairFilter};
  const detail::ContactUpdateCounts tested = contactUpdate.run(
      bodies, *broadPhase, pairs, contacts, previousContacts, apartPairs, previousApartPairs,
      contactSettings(def), dt, preSolve, filters, events, callbackError, tasks);
  lastStats.filteredPairs = tested.filteredPairs;
  lastStats.narrowPhaseTests = tested.narrowPhaseTests;
  lastStats.reusedManifolds = tested.reusedManifolds;
  time.narrowPhase = clock.lap();

  // Newton impacts need a bounciness above 0, from a body or a pre-solve callback.
  if (def.impactModel != ImpactModel::Newton || bodies.bouncyCount > 0 || preSolve)
    impacts.run(bodies, contacts, def.impactModel, tuning, def.gravity, dt);
  stepSolver.solve(bodies, contacts, joints, solverSettings(def), dt, events.faults, tasks);
  lastSubstep = dt / static_cast<float>(def.substeps);
  detail::findBrokenJoints(bodies, joints, lastSubstep, events.jointBreaks);
  for (const JointBreakEvent& broken : events.jointBreaks) {
    detail::wakeIsland(bodies, joints[broken.joint.index].bodyA);
    detail::wakeIsland(bodies, joints[broken.joint.index].bodyB);
    freeJoint(broken.joint.index);
  }
  impacts.applyTimeShifts(bodies);
  detail::applyProlongedFriction(bodies, contacts, stepSolver.solvedContacts(), def.frictionModel, dt);
  if (bodies.rollingCount > 0) detail::applyRollingResistance(bodies, contacts, stepSolver.solvedContacts());
  bodies.clearForces();
  time.solve = clock.lap();
  if (def.ccd) {
    if (!joints.empty()) detail::jointGroups(bodies, joints, jointGroups);
    detail::solveContinuous(bodies, *broadPhase, filters, tuning.linearSlop,
                            joints.empty() ? std::span<const std::uint32_t>() : jointGroups);
  }
  if (def.penetrationResponse == PenetrationResponse::Revert)
    revert.apply(bodies, *broadPhase, pairs, contacts, filters, tuning.linearSlop);
  time.continuous = clock.lap();
  detail::guardFiniteStates(bodies, events.faults, tasks);
  if (!events.faults.empty()) detail::dropFaultedContacts(events.faults, contacts, apartPairs, joints);

  proxyUpdate.refreshEscaped(bodies, *broadPhase, tuning.speculativeDistance, tasks);
  touchingCount = detail::emitContactEvents(bodies, contacts, events, def.persistEvents);
  if (bodies.sensorCount > 0)
    detail::reportSensorCrossings(bodies, *broadPhase, pairs, contacts, filters, events);
  lastStats.contactPairs = touchingCount;
  time.events = clock.lap();
  if (def.sleeping) islands.updateSleep(bodies, contacts, joints, def.sleep, dt);
  time.islands = clock.lap();
  lastStats.time = time;
  totalStats += lastStats;
}

}  // namespace collide
