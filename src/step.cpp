// One step of the world: the lecture's pipeline, one stage a call, each in the folder of its layer.
//   proxies and bounds -> broad phase -> contacts (narrow phase, manifold reuse, pre-solve) ->
//   impacts -> solve (soft step) -> friction models and rolling resistance -> continuous -> revert ->
//   fault guard -> events -> islands and sleep.
// docs/architecture.md walks one body through these stages.
#include "world_impl.h"

#include "base/log.h"
#include "base/profile.h"

#include "bodies/body_bounds.h"
#include "contacts/sensor_crossings.h"
#include "dynamics/continuous.h"
#include "dynamics/fault_guard.h"
#include "response/contact_response.h"
#include "response/revert.h"

#include <chrono>
#include <string>
#include <utility>

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

// The wall time since the last lap, for the step's stage timings, and the engine profiler's zone of
// each stage (collide/hooks.h): a lap ends the stage's zone and begins the next one's.
class StageClock {
 public:
  explicit StageClock(const char* firstStage) { beginZone(firstStage); }
  double lap(const char* nextStage) {
    endZone();
    beginZone(nextStage);
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  static void beginZone([[maybe_unused]] const char* stage) {
#if COLLIDE_PROFILE_ZONES
    if (stage) detail::profileBegin(stage);
#endif
  }
  static void endZone() {
#if COLLIDE_PROFILE_ZONES
    detail::profileEnd();
#endif
  }

  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// What the step has to tell the engine's log handler (collide/hooks.h): the bodies the fault guard
// froze, and arrays that grew (the step allocated).
void logStep(const detail::StepEvents& events, const detail::BodyStorage& bodies, std::size_t heapBefore,
             std::size_t heapAfter) {
  for (const FaultEvent& fault : events.faults) {
    detail::log(LogLevel::Warning, [&] {
      std::string fields;
      for (const auto& [bit, name] : {std::pair{FaultEvent::kPosition, "position"},
                                      {FaultEvent::kRotation, "rotation"},
                                      {FaultEvent::kLinearVelocity, "linear velocity"},
                                      {FaultEvent::kAngularVelocity, "angular velocity"}}) {
        if (fault.fields & bit) fields += (fields.empty() ? "" : ", ") + std::string(name);
      }
      const std::string& name = bodies.records[fault.body.index].name;
      return "body " + std::to_string(fault.body.index) + (name.empty() ? "" : " (" + name + ")") +
             " frozen by the fault guard: its " + fields + " stopped being finite in the step";
    });
  }
  if (heapAfter > heapBefore) {
    detail::log(LogLevel::Info, [&] {
      return "the step grew the world's arrays from " + std::to_string(heapBefore) + " to " +
             std::to_string(heapAfter) + " bytes (World::memoryUse has them by stage)";
    });
  }
}

}  // namespace

void World::Impl::step(float dt) {
  const ContactTuning& tuning = def.contact;
  // Measured only for a log handler: the world's heap before and after (arrays that grew).
  const std::size_t heapBefore = detail::logging() ? memoryUse().total() : 0;
  StageClock clock("collide: broad phase");
  StageTimes time;
  events.beginStep();
  proxyUpdate.run(bodies, *broadPhase, dt, tuning.speculativeDistance, tasks);
  lastStats = StepStats(broadPhase->findPairs(pairs, tasks));
  if (def.sleeping) detail::wakeTouchedIslands(bodies, *broadPhase, pairs, tuning.speculativeDistance, dt);
  time.broadPhase = clock.lap("collide: narrow phase");
  const detail::PairFilters filters{&jointedApart, &pairFilter};
  const detail::ContactUpdateCounts tested =
      contactUpdate.run(bodies, *broadPhase, pairs, contacts, apartPairs, contactSettings(def), dt, preSolve,
                        filters, events, callbackError, tasks);
  lastStats.filteredPairs = tested.filteredPairs;
  lastStats.narrowPhaseTests = tested.narrowPhaseTests;
  lastStats.reusedManifolds = tested.reusedManifolds;
  time.narrowPhase = clock.lap("collide: solve");

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
  time.solve = clock.lap("collide: continuous");
  if (def.ccd) {
    if (!joints.empty()) detail::jointGroups(bodies, joints, jointGroups);
    detail::solveContinuous(bodies, *broadPhase, filters, tuning.linearSlop,
                            joints.empty() ? std::span<const std::uint32_t>() : jointGroups);
  }
  if (def.penetrationResponse == PenetrationResponse::Revert)
    revert.apply(bodies, *broadPhase, pairs, contacts, filters, tuning.linearSlop);
  time.continuous = clock.lap("collide: events");
  detail::guardFiniteStates(bodies, events.faults, tasks);
  if (!events.faults.empty()) detail::dropFaultedContacts(events.faults, contacts, apartPairs, joints);

  proxyUpdate.refreshEscaped(bodies, *broadPhase, tuning.speculativeDistance, tasks);
  touchingCount = detail::emitContactEvents(bodies, contacts, events, def.persistEvents);
  if (bodies.sensorCount > 0)
    detail::reportSensorCrossings(bodies, *broadPhase, pairs, contacts, filters, events);
  lastStats.contactPairs = touchingCount;
  time.events = clock.lap("collide: islands and sleep");
  if (def.sleeping) islands.updateSleep(bodies, contacts, joints, def.sleep, dt);
  time.islands = clock.lap(nullptr);
  lastStats.time = time;
  totalStats += lastStats;
  if (detail::logging()) logStep(events, bodies, heapBefore, memoryUse().total());
}

}  // namespace collide
