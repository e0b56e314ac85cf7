// The world's settings that the layers below the world read: how materials combine, which response
// models run, and the tuning of contacts and sleep. WorldDef (world.h) gathers them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string_view>

namespace collide {

// How the two bodies' bounciness (or friction) make the pair's value.
enum class CombineRule : std::uint8_t { Average, Min, Max, Multiply };
// Newton: restitution on the normal relative velocity, friction handles the tangent.
// Interpolated: the lecture's blend of the elastic and the inelastic impact (src/response/).
enum class ImpactModel : std::uint8_t { Newton, Interpolated };
enum class FrictionModel : std::uint8_t { Coulomb, Viscous, Damping, None };
// Non-penetration (lecture, slides 10-11; docs/response.md). Soft: the soft contact pushes bodies
// apart, mass-weighted, at most ContactTuning::pushOutSpeed. Project: the same, and in the solver's
// position stage each contact's penetration beyond the linear slop is projected away at once, split
// by the lecture's mass weighting. Revert: the soft push-out, then a body still penetrating goes back
// to its last valid pose, the last at which it penetrated nothing.
enum class PenetrationResponse : std::uint8_t { Soft, Project, Revert };

// Scene-file names ("average", "newton", ...); parse functions throw Error on unknown names.
std::string_view toString(CombineRule rule);
std::string_view toString(ImpactModel model);
std::string_view toString(FrictionModel model);
std::string_view toString(PenetrationResponse response);
CombineRule parseCombineRule(std::string_view name);
ImpactModel parseImpactModel(std::string_view name);
FrictionModel parseFrictionModel(std::string_view name);
PenetrationResponse parsePenetrationResponse(std::string_view name);
// The pair's value from the two bodies' values (bounciness, friction) under `rule` (lecture, slide
// 17: "adopt some formula between the values of the two objects, e.g. avg, min, max").
constexpr float combine(CombineRule rule, float a, float b) {
  switch (rule) {
    case CombineRule::Average:
      return 0.5f * (a + b);
    case CombineRule::Min:
      return std::min(a, b);
    case CombineRule::Max:
      return std::max(a, b);
    case CombineRule::Multiply:
      return a * b;
  }
  return a;
}

// The most relax passes a substep may take (ContactTuning::relaxPasses): more would only stall the
// step, and are refused like any setting out of range.
inline constexpr int kMaxRelaxPasses = 16;

// The contact constraint's tuning (Catto, "Solver2D" 2024 / Box2D v3 soft step). Box2D's defaults
// are 30 Hz and damping ratio 10 at 4 substeps; ours are stiffer so stacks stand (see below).
struct ContactTuning {
  // Stiffness of the soft contact, capped at a quarter of the substep rate (90 Hz at 6 substeps of
  // 1/360 s). A resting point carrying force F sits F / (m_eff omega^2) deep, so the stiffness sets
  // how far a stack sags (docs/architecture.md, "Stacking").
  float hertz = 90.0f;
  // Under-damped spring, but the softness per iteration it gives (mass scale 0.80) keeps stiff
  // stacks from shivering; over-damped (10) shivers at this stiffness. Impacts do not bounce.
  float dampingRatio = 0.5f;
  float pushOutSpeed = 3.0f;          // m/s, the most the position correction may add
  float restitutionThreshold = 1.0f;  // m/s: slower impacts do not bounce (resting contacts stay quiet)
  float linearSlop = 0.005f;          // m: the penetration allowed (and the "touching" tolerance of events)
  float speculativeDistance = 0.02f;  // m: contacts are created this far apart (plus the step's motion)
  // Passes without the position bias after each substep's position update (Box2D v3's relax), so
  // that push-out does not turn into bounce. 0 to kMaxRelaxPasses.
  int relaxPasses = 1;
  // In a stack that holds a heavier body on a lighter one, each body at rest appears to the contacts
  // that carry weight as heavy as itself plus its load (src/dynamics/support_masses.h): a heavy box
  // on a light one, and a stack of any mass ratio, rest instead of sinking into themselves. Other
  // stacks are solved as they are. Off: the true masses everywhere (momentum kept in every contact).
  bool supportMasses = true;
  // A sticking friction patch holds its place: a point in each body, taken again at the patch every
  // step with the gap the patch has slipped since it stuck (so that the anchor follows a rolling
  // wheel); when the gap grows farther than this (m) along the surface, the anchor lets go and is
  // taken where the patch is.
  float frictionAnchorReach = 0.02f;
  // A pair of which no point of either body moved more than this (m) relative to the other since
  // its manifold was computed gets that manifold placed at the new poses instead of a new
  // narrow-phase query (Jolt's body pair cache), and a pair found apart stays apart: resting bodies
  // cost almost nothing. Kept well under the linear slop (what a feature the cached manifold lacks
  // could sink by) and the speculative distance (what a pair found apart could close). 0 turns the
  // cache off.
  float manifoldCacheDistance = 0.002f;
};

// When a body counts as resting (Box2D's sleep tolerances and time to sleep).
struct SleepTuning {
  float linearSpeed = 0.05f;   // m/s, of the centre of mass
  float angularSpeed = 0.05f;  // rad/s
  float timeToSleep = 0.5f;    // s every body of an island must rest before the island sleeps
};

}  // namespace collide
