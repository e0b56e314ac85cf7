// Contact data on demand (World::visitContacts) and the contact listener: the whole contact, checked
// against the physics it carries and against the events it mirrors.
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace collide {
namespace {

using test::boxBody;
using test::groundBox;
using test::sphereBody;

using test::kDt;

// A 2 kg box at rest on the ground: one contact, four points, the normal along y, and over a step the
// ground's normal impulse is the box's weight times the step, m g dt.
TEST(ContactData, ABoxAtRestCarriesItsWeightOverTheStep) {
  World world;
  const BodyId ground = world.createBody(groundBox());
  const BodyId box = world.createBody(boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 2.0f));
  for (int i = 0; i < 120; ++i) world.step(kDt);
  std::vector<ContactData> seen;
  world.visitContacts([&](const ContactData& c) { seen.push_back(c); });
  ASSERT_EQ(seen.size(), 1u);
  const ContactData& c = seen[0];
  EXPECT_TRUE((c.a == ground && c.b == box) || (c.a == box && c.b == ground));
  EXPECT_EQ(c.manifold.count, 4);
  const Vec3 up = c.a == ground ? Vec3(0.0f, 1.0f, 0.0f) : Vec3(0.0f, -1.0f, 0.0f);  // from a to b
  EXPECT_GT(glm::dot(c.manifold.normal, up), 0.9999f);
  EXPECT_NEAR(c.totalNormalImpulse(), 2.0f * 9.81f * kDt, 0.01f * 2.0f * 9.81f * kDt);
  EXPECT_LT(glm::length(c.frictionImpulse), 1e-4f);  // nothing pushes it sideways
}

// A body's contacts are exactly the world's contacts that name it, in the same order.
TEST(ContactData, ABodysContactsAreTheWorldsThatNameIt) {
  World world;
  world.createBody(groundBox());
  std::vector<BodyId> boxes;
  for (int i = 0; i < 12; ++i) {
    const Vec3 p(0.55f * float(i % 3), 0.5f + 1.05f * float(i / 3), 0.3f * float(i % 2));
    boxes.push_back(world.createBody(boxBody(p, Vec3(0.5f), 1.0f)));
  }
  for (int i = 0; i < 90; ++i) world.step(kDt);
  std::vector<std::pair<BodyId, BodyId>> all;
  world.visitContacts([&](const ContactData& c) { all.emplace_back(c.a, c.b); });
  ASSERT_GT(all.size(), boxes.size());
  for (const BodyId box : boxes) {
    std::vector<std::pair<BodyId, BodyId>> expected, got;
    for (const auto& pair : all)
      if (pair.first == box || pair.second == box) expected.push_back(pair);
    world.visitContacts(box, [&](const ContactData& c) { got.emplace_back(c.a, c.b); });
    EXPECT_EQ(got, expected);
  }
  EXPECT_COLLIDE_ERROR(world.visitContacts(BodyId{}, [](const ContactData&) {}));
}

struct Recorder : ContactListener {
  struct Call {
    ContactEvent::Type type;
    BodyId a, b;
    Vec3 normal;
    float impulse;
    int points;
  };
  std::vector<Call> calls;
  void onBegin(const ContactData& c) override {
    calls.push_back(
        {ContactEvent::Type::Begin, c.a, c.b, c.manifold.normal, c.totalNormalImpulse(), c.manifold.count});
  }
  void onPersist(const ContactData& c) override {
    calls.push_back(
        {ContactEvent::Type::Persist, c.a, c.b, c.manifold.normal, c.totalNormalImpulse(), c.manifold.count});
  }
  void onEnd(const ContactEvent& e) override {
    calls.push_back({ContactEvent::Type::End, e.a, e.b, e.normal, 0.0f, 0});
  }
};

// The listener is told of exactly the step's events, in their order, with the manifold behind each:
// balls bouncing on the ground and off each other begin, persist and end contacts.
TEST(ContactData, TheListenerMirrorsTheEventsWithTheWholeContact) {
  WorldDef def;
  def.persistEvents = true;
  World world(def);
  world.createBody(groundBox());
  for (int i = 0; i < 6; ++i) {
    BodyDef ball = sphereBody(Vec3(0.3f * float(i), 1.0f + 1.1f * float(i), 0.1f * float(i % 2)), 0.5f, 1.0f);
    ball.bounciness = 0.6f;
    world.createBody(ball);
  }
  Recorder recorder;
  world.setContactListener(&recorder);
  int begins = 0, persists = 0, ends = 0;
  for (int step = 0; step < 240; ++step) {
    recorder.calls.clear();
    world.step(kDt);
    const auto events = world.contactEvents();
    ASSERT_EQ(recorder.calls.size(), events.size()) << "step " << step;
    for (std::size_t i = 0; i < events.size(); ++i) {
      const Recorder::Call& call = recorder.calls[i];
      EXPECT_EQ(call.type, events[i].type);
      EXPECT_EQ(call.a, events[i].a);
      EXPECT_EQ(call.b, events[i].b);
      EXPECT_EQ(call.normal, events[i].normal);
      if (call.type == ContactEvent::Type::End) {
        ++ends;
        continue;
      }
      (call.type == ContactEvent::Type::Begin ? begins : persists) += 1;
      EXPECT_GT(call.points, 0);
      EXPECT_FLOAT_EQ(call.impulse, events[i].impulse);
    }
  }
  EXPECT_GT(begins, 6);  // each ball lands, some bounce and land again
  EXPECT_GT(persists, 100);
  EXPECT_GT(ends, 0);
  world.setContactListener(nullptr);
  recorder.calls.clear();
  world.step(kDt);
  EXPECT_TRUE(recorder.calls.empty());
}

}  // namespace
}  // namespace collide
