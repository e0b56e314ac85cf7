// The step's fault guard (dynamics/fault_guard.h) over many bodies: it looks at them in parallel
// ranges and freezes and reports in body order, so every worker count gives the same events.
#include "dynamics/fault_guard.h"
#include "base/task_runner.h"
#include "bodies/body_def.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace collide {
namespace {

TEST(FaultGuardRanges, NonFiniteBodiesInSeveralRangesAreFrozenAndReportedInBodyOrder) {
  constexpr std::uint32_t kBodies = 9000;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const int workers : {1, 3}) {
    detail::BodyStorage bodies;
    for (std::uint32_t i = 0; i < kBodies; ++i) {
      const std::uint32_t index = bodies.allocate();
      BodyDef def;
      def.shape = Shape(Sphere{0.5f});
      def.position = Vec3(float(i), 0.0f, 0.0f);
      detail::initBody(def, bodies.records[index], bodies.states[index]);
    }
    // Faults far apart (several ranges at any split), one of each kind of field.
    bodies.states[17].linearVelocity.x = nan;
    bodies.states[4500].angularVelocity.y = nan;
    bodies.states[8999].centerOfMass.z = nan;
    detail::TaskRunner tasks;
    tasks.configure(workers, nullptr, nullptr, nullptr);
    Array<FaultEvent> faults;
    detail::guardFiniteStates(bodies, faults, tasks);
    ASSERT_EQ(faults.size(), 3u) << workers << " workers";
    EXPECT_EQ(faults[0].body.index, 17u);
    EXPECT_EQ(faults[0].fields, FaultEvent::kLinearVelocity);
    EXPECT_EQ(faults[1].body.index, 4500u);
    EXPECT_EQ(faults[1].fields, FaultEvent::kAngularVelocity);
    EXPECT_EQ(faults[2].body.index, 8999u);
    EXPECT_EQ(faults[2].fields, FaultEvent::kPosition);
    for (const FaultEvent& fault : faults) {
      EXPECT_EQ(detail::nonFiniteFields(bodies.states[fault.body.index]), 0) << "frozen at a finite state";
      EXPECT_FALSE(bodies.records[fault.body.index].awake);
    }
    // Nothing else was touched, and a second look finds nothing.
    faults.clear();
    detail::guardFiniteStates(bodies, faults, tasks);
    EXPECT_TRUE(faults.empty());
  }
}

}  // namespace
}  // namespace collide
