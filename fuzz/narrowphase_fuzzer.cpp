// Narrow-phase fuzzer: two shapes of any of the ten types (fuzz_input.h: degenerate ones and
// extreme or non-finite numbers included) at arbitrary placements, through every pair query of
// include/collide/narrowphase.h: overlap(), collide(), distance() and timeOfImpact().
//
// Allowed: a result, or collide::Error (a shape or transform the API refuses, NaN anywhere, a pair
// the table does not support). A finding (aborted on, so libFuzzer keeps the input): a crash, a
// sanitizer report, another exception, or a result that breaks the documented contract:
//   collide(): at most 4 points, returns count > 0;
//   timeOfImpact(): t in [0, 1] unless it is NaN;
// and, for input within the working range (no extreme value: FuzzInput::sawExtreme; beyond it
// float precision and range run out, docs/reliability.md):
//   collide(): a finite unit normal, finite points and depths;
//   overlap(): never false for a pair collide() reports as penetrating;
//   distance(): finite distance and points, a unit normal;
//   timeOfImpact(): a finite t, a finite unit normal and point on a hit.
#include "fuzz_input.h"

#include <collide/narrowphase.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {

using namespace collide;

bool isUnit(const Vec3& v) { return isFinite(v) && std::abs(glm::length(v) - 1.0f) < 1e-3f; }

void checkManifold(const Manifold& m, bool reported, bool inWorkingRange) {
  if (m.count < 0 || m.count > Manifold::kMaxPoints) std::abort();
  if (reported != (m.count > 0)) std::abort();
  if (m.count == 0 || !inWorkingRange) return;
  if (!isUnit(m.normal)) std::abort();
  for (int i = 0; i < m.count; ++i) {
    const ContactPoint& p = m.points[i];
    if (!std::isfinite(p.depth) || !isFinite(p.pointOnA) || !isFinite(p.pointOnB)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  collide::fuzz::FuzzInput in(data, size);
  try {
    const Shape a = collide::fuzz::decodeShape(in, /*allowPlane=*/true);
    const Transform ta = in.transform(3.0f);
    const Shape b = collide::fuzz::decodeShape(in, /*allowPlane=*/true);
    const Transform tb = in.transform(3.0f);
    const float margin = in.value(0.0f, 0.5f);
    const bool sane = !in.sawExtreme();
    if (collide::fuzz::tracing()) {
      using collide::fuzz::describe;
      std::fprintf(stderr, "A: %s at %s\nB: %s at %s\nmargin %s%s\n", describe(a).c_str(),
                   describe(ta).c_str(), describe(b).c_str(), describe(tb).c_str(), describe(margin).c_str(),
                   sane ? "" : " (extreme values)");
    }

    // Each query on its own: one refusing the input (distance() on a mesh) must not hide the others.
    Manifold m;
    bool penetrating = false;
    try {
      const bool reported = collide::collide(a, ta, b, tb, m, margin);
      checkManifold(m, reported, sane);
      penetrating = reported && m.maxDepth() > 0.0f;
    } catch (const Error&) {
    }
    try {
      if (!overlap(a, ta, b, tb) && penetrating && sane) std::abort();
    } catch (const Error&) {
    }
    try {
      const DistanceResult d = distance(a, ta, b, tb);
      if (sane && (!std::isfinite(d.distance) || !isFinite(d.pointOnA) || !isFinite(d.pointOnB)))
        std::abort();
      if (sane && !isUnit(d.normal)) std::abort();
    } catch (const Error&) {
    }
    try {
      // B moves from tb to a second placement; A stays (the world's sweeps are relative anyway).
      Transform tb1 = tb;
      tb1.position += in.vec(-4.0f, 4.0f);
      tb1.rotation = in.rotation();
      const bool saneSweep = !in.sawExtreme();
      const ToiResult toi = timeOfImpact(a, Sweep::fixed(ta), b, Sweep::between(tb, tb1));
      if (std::isfinite(toi.t) && !(toi.t >= 0.0f && toi.t <= 1.0f)) std::abort();
      if (saneSweep && !std::isfinite(toi.t)) std::abort();
      const bool hit = toi.state != ToiResult::State::Separated;
      if (saneSweep && hit && (!isUnit(toi.normal) || !isFinite(toi.point))) std::abort();
    } catch (const Error&) {
    }
  } catch (const Error&) {
    // A shape or transform the API refused: the contract holds.
  }
  return 0;
}
