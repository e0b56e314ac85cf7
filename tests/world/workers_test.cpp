// The world at several workers (WorldDef::workerCount, include/collide/tasks.h): bad counts are
// refused; one worker starts no thread; and a pile of boxes and spheres, or chains on joints, stepped
// on one worker, on the world's own threads or on an engine's job system ends bit for bit in the same
// state.
#include "support/collide_error.h"
#include "support/test_job_system.h"
#include "support/world_helpers.h"

#include "dynamics/solver.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <vector>

namespace collide {
namespace {

using test::kDt;

std::size_t threadCount() {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++count;
  return count;
}

// 6 x 6 x 6 boxes and spheres dropped in a loose lattice on a ground box, and a jointed chain.
std::vector<BodyId> buildMixedPile(World& world) {
  world.createBody(test::groundBox());
  std::vector<BodyId> bodies;
  for (int x = 0; x < 6; ++x) {
    for (int y = 0; y < 6; ++y) {
      for (int z = 0; z < 6; ++z) {
        const Vec3 at(0.55f * float(x) + 0.05f * float(y % 2), 0.6f + 0.55f * float(y), 0.55f * float(z));
        bodies.push_back(world.createBody((x + y + z) % 2 == 0 ? test::boxBody(at, Vec3(0.25f), 1.0f)
                                                               : test::sphereBody(at, 0.25f, 1.0f)));
      }
    }
  }
  BodyId previous = test::staticAnchor(world, Vec3(-2.0f, 5.0f, 0.0f));
  for (int i = 0; i < 8; ++i) {
    const BodyId link =
        world.createBody(test::sphereBody(Vec3(-2.0f + 0.3f * float(i + 1), 5.0f, 0.0f), 0.1f, 0.2f));
    world.createBallJoint({previous, link, Vec3(-2.0f + 0.3f * float(i) + 0.15f, 5.0f, 0.0f)});
    bodies.push_back(link);
    previous = link;
  }
  return bodies;
}

std::vector<unsigned char> runPile(WorldDef def, int steps, int switchWorkersAt = -1, int switchTo = 1) {
  World world(def);
  const std::vector<BodyId> bodies = buildMixedPile(world);
  for (int step = 0; step < steps; ++step) {
    if (step == switchWorkersAt) {
      def.workerCount = switchTo;
      world.setDef(def);
    }
    world.step(kDt);
  }
  return test::stateBytes(world, bodies);
}

TEST(Workers, BadCountsAndHalfAJobSystemAreRefused) {
  WorldDef def;
  def.workerCount = 0;
  EXPECT_COLLIDE_ERROR(World{def});
  def.workerCount = kMaxWorkers + 1;
  if (const std::optional<std::string> error = ::collide::test::errorOf([&] { World world(def); }); !error) {
    ADD_FAILURE() << "65 workers accepted";
  } else {
    EXPECT_STREQ(error->c_str(), "world: workerCount must be 1 to 64, got 65");
  }
  def.workerCount = 2;
  def.enqueueTask = &test::TestJobSystem::enqueue;
  EXPECT_COLLIDE_ERROR(World{def});
  World world;
  EXPECT_COLLIDE_ERROR(world.setDef(def));
  EXPECT_EQ(world.def().workerCount, 1);  // unchanged
}

TEST(Workers, OneWorkerStartsNoThreadAndFourStartThree) {
  const std::size_t before = threadCount();
  {
    World world;
    buildMixedPile(world);
    for (int step = 0; step < 5; ++step) world.step(kDt);
    EXPECT_EQ(threadCount(), before);
  }
  WorldDef def;
  def.workerCount = 4;
  {
    World world(def);
    EXPECT_EQ(threadCount(), before + 3);
  }
  EXPECT_EQ(threadCount(), before);  // joined with the world
}

// A world definition that steps on the test's own job system with `workers` workers.
WorldDef onJobSystem(test::TestJobSystem& jobs, int workers) {
  WorldDef def;
  def.workerCount = workers;
  def.enqueueTask = &test::TestJobSystem::enqueue;
  def.finishTask = &test::TestJobSystem::finish;
  def.userTaskContext = &jobs;
  return def;
}

// run(def) at 2, 3 and 8 workers of the world's own threads gives `one`, bit for bit.
template <typename Run>
void expectTheStateOfOneWorker(const std::vector<unsigned char>& one, Run run) {
  for (const int workers : {2, 3, 8}) {
    WorldDef def;
    def.workerCount = workers;
    EXPECT_TRUE(run(def) == one) << workers << " workers";
  }
}

TEST(Workers, APileEndsInTheSameStateOnEveryWorkerCount) {
  const std::vector<unsigned char> one = runPile(WorldDef{}, 240);
  expectTheStateOfOneWorker(one, [](const WorldDef& def) { return runPile(def, 240); });
}

// The fault guard looks at the bodies in parallel ranges: with bodies enough for several ranges and
// faults in more than one of them, every worker count freezes the same bodies and reports them in
// body order.
// Spheres rained onto the ground in a loose, jittered lattice, some bouncy: contacts begin, end
// and come back all through the run, so the narrow phase's walk in blocks (several workers) meets
// new contacts ahead of vanished ones in every block, and blocks that grow and shrink. Each step's
// contact events, and the whole world's bytes (a snapshot: every contact and pair apart, in order)
// at the end, are the one walk's.
struct RainRecord {
  std::vector<unsigned char> events;
  std::vector<std::uint8_t> snapshot;
};
RainRecord runRain(int workers) {
  WorldDef def;
  def.workerCount = workers;
  World world(def);
  world.createBody(test::groundBox());
  std::uint32_t seed = 12345;
  const auto jitter = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 24) - 0.5f;
  };
  for (int i = 0; i < 900; ++i) {
    const Vec3 at(0.6f * float(i % 15) + 0.1f * jitter(), 0.6f + 0.6f * float(i / 225),
                  0.6f * float((i / 15) % 15) + 0.1f * jitter());
    BodyDef body = test::sphereBody(at, 0.25f, 1.0f, Vec3(jitter(), -2.0f, jitter()));
    if (i % 3 == 0) body.bounciness = 0.8f;
    world.createBody(body);
  }
  RainRecord record;
  for (int step = 0; step < 90; ++step) {
    world.step(kDt);
    for (const ContactEvent& e : world.contactEvents()) {
      const auto append = [&](const auto& field) {
        const auto* p = reinterpret_cast<const unsigned char*>(&field);
        record.events.insert(record.events.end(), p, p + sizeof field);
      };
      append(e.type);
      append(e.a.index);
      append(e.b.index);
      append(e.partA);
      append(e.partB);
      append(e.point);
      append(e.normal);
      append(e.impulse);
      append(e.speed);
    }
  }
  record.snapshot = world.saveSnapshot();
  return record;
}

TEST(Workers, TheNarrowPhaseInBlocksGivesTheSameContactsAndEvents) {
  const RainRecord one = runRain(1);
  ASSERT_GT(one.events.size(), 500u * 50u) << "contacts begin and end all through";
  for (const int workers : {2, 3, 8}) {
    const RainRecord many = runRain(workers);
    EXPECT_TRUE(many.events == one.events) << workers << " workers: the contact events";
    EXPECT_TRUE(many.snapshot == one.snapshot) << workers << " workers: the world's bytes";
  }
}

TEST(Workers, FaultsInSeveralRangesAreReportedInBodyOrderOnEveryWorkerCount) {
  constexpr float kHuge = 3.0e38f;  // finite; two of them add up to infinity
  std::vector<BodyId> expected;
  for (const int workers : {1, 3}) {
    WorldDef def;
    def.workerCount = workers;
    World world(def);
    std::vector<BodyId> bodies;
    for (int i = 0; i < 6000; ++i) {
      const Vec3 at(3.0f * float(i % 80), 3.0f * float(i / 80), 0.0f);
      bodies.push_back(world.createBody(test::sphereBody(at, 0.5f, 1.0f)));
    }
    std::vector<BodyId> faulty;
    for (int i = 5999; i >= 0; i -= 997) {  // the last first: the report is in body order all the same
      const Vec3 center = world.centerOfMass(bodies[static_cast<std::size_t>(i)]);
      world.applyForce(bodies[static_cast<std::size_t>(i)], Vec3(kHuge, 0.0f, 0.0f), center);
      world.applyForce(bodies[static_cast<std::size_t>(i)], Vec3(kHuge, 0.0f, 0.0f), center);
      faulty.insert(faulty.begin(), bodies[static_cast<std::size_t>(i)]);
    }
    world.step(kDt);
    std::vector<BodyId> reported;
    for (const FaultEvent& fault : world.faultEvents()) reported.push_back(fault.body);
    EXPECT_EQ(reported, faulty) << workers << " workers";
    for (const BodyId id : faulty) EXPECT_EQ(world.linearVelocity(id), Vec3(0.0f)) << workers << " workers";
    if (workers == 1) expected = reported;
    EXPECT_EQ(reported, expected);
  }
}

TEST(Workers, AnEnginesJobSystemGivesTheSameState) {
  const std::vector<unsigned char> one = runPile(WorldDef{}, 240);
  test::TestJobSystem jobs(3);
  EXPECT_TRUE(runPile(onJobSystem(jobs, 3), 240) == one);
  // The contact batches' fill went through it once a step from the first contacts on (this pile's
  // colours are too small for the solver's passes to be split).
  EXPECT_GT(jobs.tasks(), 200);
}

// 12 x 12 stacks of 10 boxes, resting on each other and side by side from the start: one island
// (solver_blocks.h) of about 1,000 contacts a colour, so that every pass of the solver splits its
// colours into ranges.
std::vector<unsigned char> runStacks(const WorldDef& def, int steps) {
  World world(def);
  world.createBody(test::groundBox());
  std::vector<BodyId> boxes;
  for (int x = 0; x < 12; ++x) {
    for (int z = 0; z < 12; ++z) {
      for (int y = 0; y < 10; ++y) {
        const Vec3 at(0.5f * float(x) - 2.75f, 0.25f + 0.5f * float(y), 0.5f * float(z) - 2.75f);
        boxes.push_back(world.createBody(test::boxBody(at, Vec3(0.25f), 1.0f)));
      }
    }
  }
  for (int step = 0; step < steps; ++step) world.step(kDt);
  return test::stateBytes(world, boxes);
}

TEST(Workers, StacksWhoseColoursSplitIntoRangesEndInTheSameState) {
  const std::vector<unsigned char> one = runStacks(WorldDef{}, 30);
  WorldDef def;
  def.workerCount = 2;
  EXPECT_TRUE(runStacks(def, 30) == one);
  test::TestJobSystem jobs(2);
  EXPECT_TRUE(runStacks(onJobSystem(jobs, 2), 30) == one);
  // More tasks than steps times substeps times passes: the solver's passes went through it.
  EXPECT_GT(jobs.tasks(), 30 * 6 * 4);
}

// Islands the solver takes in blocks (solver_blocks.h): a kinematic platform carrying two stacks,
// a carpet of boxes side by side (one island of more contacts than a block), 60 stacks apart from
// each other, spheres falling free, a jointed chain and a hinge (the joints' block), and the
// platform's stacks made last, so that only their contacts with the platform put them in its block. Solved in
// blocks (on one worker, or several blocks at a time on the world's threads or an engine's job system) and as
// one block, it ends bit for bit in the same state.
std::vector<unsigned char> runIslands(const WorldDef& def, int steps, std::uint32_t* blocks = nullptr) {
  World world(def);
  world.createBody(test::groundBox());
  std::vector<BodyId> bodies;
  BodyDef platform = test::boxBody(Vec3(-20.0f, 3.0f, 0.0f), Vec3(1.5f, 0.1f, 1.5f), 1.0f);
  platform.type = BodyType::Kinematic;
  platform.linearVelocity = Vec3(0.5f, 0.0f, 0.2f);
  platform.angularVelocity = Vec3(0.0f, 0.3f, 0.0f);
  bodies.push_back(world.createBody(platform));
  for (int x = 0; x < 14; ++x) {
    for (int z = 0; z < 14; ++z) {
      for (int y = 0; y < 2; ++y) {
        const Vec3 at(0.5f * float(x) - 3.25f, 0.25f + 0.5f * float(y), 0.5f * float(z) - 3.25f);
        bodies.push_back(world.createBody(test::boxBody(at, Vec3(0.25f), 1.0f)));
      }
    }
  }
  for (int i = 0; i < 60; ++i) {
    const float x = 2.0f * float(i % 10) - 9.0f;
    const float z = 6.0f + 2.0f * float(i / 10);
    for (int y = 0; y < 3; ++y) {
      const Vec3 at(x + 0.02f * float(y), 0.25f + 0.5f * float(y), z);
      bodies.push_back(world.createBody(test::boxBody(at, Vec3(0.25f), 1.0f + 0.5f * float(y))));
    }
  }
  for (int i = 0; i < 8; ++i)
    bodies.push_back(
        world.createBody(test::sphereBody(Vec3(3.0f * float(i) - 10.0f, 6.0f, -8.0f), 0.3f, 1.0f)));
  // A chain of boxes on ball joints from a static anchor, swinging onto a box on the ground, and two
  // boxes apart from each other joined by a hinge: the joints' block.
  BodyId previous = test::staticAnchor(world, Vec3(15.0f, 4.0f, 0.0f));
  for (int i = 0; i < 4; ++i) {
    const BodyId link =
        world.createBody(test::boxBody(Vec3(15.6f + 0.6f * float(i), 4.0f, 0.0f), Vec3(0.25f), 1.0f));
    world.createBallJoint({previous, link, Vec3(15.3f + 0.6f * float(i), 4.0f, 0.0f)});
    bodies.push_back(link);
    previous = link;
  }
  bodies.push_back(world.createBody(test::boxBody(Vec3(15.0f, 0.5f, 0.0f), Vec3(0.5f), 3.0f)));
  const BodyId left = world.createBody(test::boxBody(Vec3(20.0f, 0.25f, 5.0f), Vec3(0.25f), 1.0f));
  const BodyId right = world.createBody(test::boxBody(Vec3(20.6f, 1.0f, 5.0f), Vec3(0.25f), 1.0f));
  HingeJointDef hinge;
  hinge.a = left;
  hinge.b = right;
  hinge.anchor = Vec3(20.3f, 0.6f, 5.0f);
  world.createHingeJoint(hinge);
  bodies.push_back(left);
  bodies.push_back(right);
  for (const float x : {-20.6f, -19.4f}) {
    for (int y = 0; y < 2; ++y) {
      const Vec3 at(x, 3.35f + 0.5f * float(y), 0.3f);
      bodies.push_back(world.createBody(test::boxBody(at, Vec3(0.25f), 2.0f)));
    }
  }
  for (int step = 0; step < steps; ++step) world.step(kDt);
  if (blocks != nullptr) *blocks = detail::lastSolveBlockCount();
  return test::stateBytes(world, bodies);
}

TEST(Workers, IslandsSolvedInBlocksEndAsSolvedTogether) {
  detail::setSolveInBlocks(false);
  std::uint32_t blocks = 0;
  const std::vector<unsigned char> together = runIslands(WorldDef{}, 90, &blocks);
  detail::setSolveInBlocks(true);
  EXPECT_EQ(blocks, 1u);
  EXPECT_TRUE(runIslands(WorldDef{}, 90, &blocks) == together);
  // The joints', the platform's, the carpet (a large island, its own block) and the stacks' and
  // spheres' after it.
  EXPECT_GE(blocks, 4u);
  expectTheStateOfOneWorker(together, [](const WorldDef& def) { return runIslands(def, 90); });
  test::TestJobSystem jobs(2);
  EXPECT_TRUE(runIslands(onJobSystem(jobs, 2), 90) == together);
}

// 96 chains of four boxes hanging from static anchors and swung into one another: on hinges with
// limits, a motor and friction (their rigid rows solved as 96 joint trees side by side, the rest
// in the Gauss-Seidel waves), every third chain on soft ball joints (Gauss-Seidel only). The
// joints are created a level at a time (every chain's top joint, then every chain's second...), so
// each wave holds one level, 96 joints, more than one parallel range, and a joint's neighbours in
// its chain are far from it in joint order: a wave that let a chain's joints run side by side
// would race, and its order would differ from one joint after another.
std::vector<unsigned char> runChains(WorldDef def, int steps) {
  World world(def);
  world.createBody(test::groundBox());
  constexpr int kChains = 96;
  constexpr int kLinks = 4;
  std::vector<BodyId> anchors;
  std::vector<BodyId> bodies;  // chain after chain, top link first
  for (int chain = 0; chain < kChains; ++chain) {
    const float x = 0.3f * float(chain % 24);
    const float z = 0.9f * float(chain / 24);
    anchors.push_back(test::staticAnchor(world, Vec3(x, 4.0f, z)));
    for (int link = 0; link < kLinks; ++link) {
      BodyDef box = test::boxBody(Vec3(x, 3.8f - 0.4f * float(link), z), Vec3(0.1f, 0.18f, 0.1f), 1.0f);
      box.linearVelocity = Vec3(chain % 2 == 0 ? 1.5f : -1.5f, 0.0f, 0.5f * float(link));
      bodies.push_back(world.createBody(box));
    }
  }
  for (int link = 0; link < kLinks; ++link) {
    for (int chain = 0; chain < kChains; ++chain) {
      const BodyId body = bodies[static_cast<std::size_t>(chain * kLinks + link)];
      const BodyId above = link == 0 ? anchors[static_cast<std::size_t>(chain)]
                                     : bodies[static_cast<std::size_t>(chain * kLinks + link - 1)];
      const Vec3 anchor = world.transform(body).position + Vec3(0.0f, 0.2f, 0.0f);
      if (chain % 3 == 2) {
        BallJointDef ball{.a = above, .b = body, .anchor = anchor};
        ball.softness = {20.0f, 0.7f};
        ball.frictionTorque = 0.05f;
        world.createBallJoint(ball);
      } else {
        HingeJointDef hinge{.a = above, .b = body, .anchor = anchor, .axis = Vec3(0.0f, 0.0f, 1.0f)};
        hinge.limits = {true, -0.6f, 0.6f};
        hinge.frictionTorque = 0.02f;
        if (link == 0) hinge.motor = {true, 2.0f, 5.0f};
        world.createHingeJoint(hinge);
      }
    }
  }
  for (int step = 0; step < steps; ++step) world.step(kDt);
  return test::stateBytes(world, bodies);
}

TEST(Workers, JointWavesAndTreesInParallelEndInTheSameState) {
  const std::vector<unsigned char> one = runChains(WorldDef{}, 60);
  expectTheStateOfOneWorker(one, [](const WorldDef& def) { return runChains(def, 60); });
  test::TestJobSystem jobs(2);
  EXPECT_TRUE(runChains(onJobSystem(jobs, 2), 60) == one) << "an engine's job system";
}

// 64 particles, each on a rope to a static anchor, with two chains of two boxes hanging from it on
// ball joints, all the left chains created before all the right ones (so that a particle's two trees
// fall in different ranges of trees). A particle is no ground for a joint tree (its rows would move
// it): were it one, the particle's two trees, solved side by side, would both write it (a race
// ThreadSanitizer reports). Its joints are Gauss-Seidel's instead.
std::vector<unsigned char> runChainsOnParticles(const WorldDef& def, int steps) {
  World world(def);
  std::vector<BodyId> bodies;
  std::vector<Vec3> tops;
  for (int i = 0; i < 64; ++i) {
    const Vec3 top(1.5f * float(i % 8), 4.0f, 1.5f * float(i / 8));
    const BodyId anchor = test::staticAnchor(world, top + Vec3(0.0f, 1.0f, 0.0f));
    BodyDef particleDef = test::sphereBody(top, 0.05f, 0.5f, Vec3(0.5f, 0.0f, 0.0f));
    particleDef.particle = true;
    const BodyId particle = world.createBody(particleDef);
    world.createDistanceConstraint({.a = anchor, .b = particle});
    bodies.push_back(particle);
    tops.push_back(top);
  }
  for (const float side : {-1.0f, 1.0f}) {
    for (std::size_t i = 0; i < tops.size(); ++i) {
      BodyId above = bodies[i];
      for (int link = 0; link < 2; ++link) {
        const Vec3 at = tops[i] + Vec3(0.3f * side * float(link + 1), -0.3f * float(link + 1), 0.0f);
        const BodyId box = world.createBody(test::boxBody(at, Vec3(0.08f), 1.0f));
        // A particle's joint holds its centre.
        const Vec3 anchor = link == 0 ? tops[i] : at + Vec3(-0.15f * side, 0.15f, 0.0f);
        world.createBallJoint({.a = above, .b = box, .anchor = anchor});
        bodies.push_back(box);
        above = box;
      }
    }
  }
  for (int step = 0; step < steps; ++step) world.step(kDt);
  return test::stateBytes(world, bodies);
}

TEST(Workers, TreesHangingFromOneParticleEndInTheSameState) {
  const std::vector<unsigned char> one = runChainsOnParticles(WorldDef{}, 60);
  expectTheStateOfOneWorker(one, [](const WorldDef& def) { return runChainsOnParticles(def, 60); });
}

TEST(Workers, ChangingTheWorkerCountBetweenStepsChangesNothing) {
  const std::vector<unsigned char> one = runPile(WorldDef{}, 200);
  EXPECT_TRUE(runPile(WorldDef{}, 200, 100, 4) == one);
  WorldDef def;
  def.workerCount = 3;
  EXPECT_TRUE(runPile(def, 200, 100, 1) == one);
}

}  // namespace
}  // namespace collide
