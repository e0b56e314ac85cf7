// The world's definition: its validation, and the scene-file names of the settings enums.
#include <collide/body.h>
#include <collide/error.h>
#include <collide/settings.h>

#include "base/fail.h"
#include "base/format.h"
#include "broadphase/broad_phase_internal.h"
#include "world_impl.h"

#include <array>
#include <string>

namespace collide {

namespace {

template <class Enum, std::size_t N>
Enum parseName(std::string_view name, const std::array<std::string_view, N>& names, const char* what) {
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) expected += (i ? ", " : "") + std::string(names[i]);
  COLLIDE_FAIL(
      std::string(what) + ": unknown name \"" + std::string(name) + "\", expected one of " + expected,
      static_cast<Enum>(0));
}

constexpr std::array<std::string_view, 4> kCombineNames{"average", "min", "max", "multiply"};
constexpr std::array<std::string_view, 2> kImpactNames{"newton", "interpolated"};
constexpr std::array<std::string_view, 4> kFrictionNames{"coulomb", "viscous", "damping", "none"};
constexpr std::array<std::string_view, 3> kPenetrationNames{"soft", "project", "revert"};
constexpr std::array<std::string_view, 3> kBodyTypeNames{"static", "kinematic", "dynamic"};
constexpr std::array<std::string_view, 6> kJointTypeNames{"distance", "ball",  "hinge",
                                                          "slider",   "fixed", "cone"};

}  // namespace

std::string_view toString(CombineRule rule) { return kCombineNames[static_cast<int>(rule)]; }
std::string_view toString(ImpactModel model) { return kImpactNames[static_cast<int>(model)]; }
std::string_view toString(FrictionModel model) { return kFrictionNames[static_cast<int>(model)]; }
std::string_view toString(PenetrationResponse response) {
  return kPenetrationNames[static_cast<int>(response)];
}
std::string_view toString(BodyType type) { return kBodyTypeNames[static_cast<int>(type)]; }
std::string_view toString(JointType type) { return kJointTypeNames[static_cast<int>(type)]; }

CombineRule parseCombineRule(std::string_view name) {
  return parseName<CombineRule>(name, kCombineNames, "combine rule");
}
ImpactModel parseImpactModel(std::string_view name) {
  return parseName<ImpactModel>(name, kImpactNames, "impact model");
}
FrictionModel parseFrictionModel(std::string_view name) {
  return parseName<FrictionModel>(name, kFrictionNames, "friction model");
}
PenetrationResponse parsePenetrationResponse(std::string_view name) {
  return parseName<PenetrationResponse>(name, kPenetrationNames, "penetration response");
}

bool validateWorldDef(const WorldDef& def) {
  using detail::formatFloat;
  if (!isFinite(def.gravity))
    COLLIDE_FAIL("world: gravity must be finite, got " + detail::formatVec(def.gravity), false);
  if (def.substeps < 1 || def.substeps > kMaxSubsteps)
    COLLIDE_FAIL("world: substeps must be 1 to " + std::to_string(kMaxSubsteps) + ", got " +
                     std::to_string(def.substeps),
                 false);
  if (def.workerCount < 1 || def.workerCount > kMaxWorkers)
    COLLIDE_FAIL("world: workerCount must be 1 to " + std::to_string(kMaxWorkers) + ", got " +
                     std::to_string(def.workerCount),
                 false);
  if ((def.enqueueTask == nullptr) != (def.finishTask == nullptr))
    COLLIDE_FAIL("world: enqueueTask and finishTask come together (one is set, the other null)", false);
  const ContactTuning& t = def.contact;
  const auto check = [](float value, bool ok, const char* field) {
    if (!isFinite(value) || !ok)
      COLLIDE_FAIL(std::string("world: contact.") + field + " out of range, got " + formatFloat(value),
                   false);
    return true;
  };
  const bool contactValid =
      check(t.hertz, t.hertz > 0.0f, "hertz (must be > 0)") &&
      check(t.dampingRatio, t.dampingRatio >= 0.0f, "dampingRatio (must be >= 0)") &&
      check(t.pushOutSpeed, t.pushOutSpeed > 0.0f, "pushOutSpeed (must be > 0)") &&
      check(t.restitutionThreshold, t.restitutionThreshold >= 0.0f, "restitutionThreshold (must be >= 0)") &&
      check(t.linearSlop, t.linearSlop >= 0.0f, "linearSlop (must be >= 0)") &&
      check(t.speculativeDistance, t.speculativeDistance >= 0.0f, "speculativeDistance (must be >= 0)") &&
      check(t.frictionAnchorReach, t.frictionAnchorReach >= 0.0f, "frictionAnchorReach (must be >= 0)") &&
      check(t.manifoldCacheDistance, t.manifoldCacheDistance >= 0.0f, "manifoldCacheDistance (must be >= 0)");
  if (!contactValid) return false;
  if (t.relaxPasses < 0 || t.relaxPasses > kMaxRelaxPasses)
    COLLIDE_FAIL("world: contact.relaxPasses out of range (must be 0 to " + std::to_string(kMaxRelaxPasses) +
                     "), got " + std::to_string(t.relaxPasses),
                 false);
  const SleepTuning& sleep = def.sleep;
  const auto checkSleep = [](float value, bool ok, const char* field) {
    if (!isFinite(value) || !ok)
      COLLIDE_FAIL(std::string("world: sleep.") + field + " out of range, got " + formatFloat(value), false);
    return true;
  };
  return checkSleep(sleep.linearSpeed, sleep.linearSpeed >= 0.0f, "linearSpeed (must be >= 0)") &&
         checkSleep(sleep.angularSpeed, sleep.angularSpeed >= 0.0f, "angularSpeed (must be >= 0)") &&
         checkSleep(sleep.timeToSleep, sleep.timeToSleep > 0.0f, "timeToSleep (must be > 0)") &&
         detail::validateBroadPhaseSettings(def.broadPhase);
}

}  // namespace collide
