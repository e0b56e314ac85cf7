// Joint trees solved directly (src/dynamics/joint_tree.h) against known answers: a
// 50-link chain released from the horizontal stretches less than 1 % in total; a 100 kg ball under
// 20 links of 0.1 kg stays within 2 % of the chain's length, at rest and swinging; internal joint
// forces keep a tumbling free chain's linear and angular momentum; a chain built from its free end
// up is solved as a tree too; a grid of joints (a mesh) is left to Gauss-Seidel whole, a ladder keeps
// its tree; a chain of alternating 100 kg and 0.1 kg links gains no energy as it swings.
#include "support/world_helpers.h"

#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace collide {
namespace {

using test::kDt;

struct Chain {
  World world;
  std::vector<BodyId> links;
  std::vector<JointId> joints;
};

// `count` links of `linkLength` and `linkMass`, ball-jointed end to end along `direction` from a
// static anchor at `top` (or free, with no anchor).
void buildChain(Chain& chain, const Vec3& top, const Vec3& direction, int count, float linkLength,
                float linkMass, bool anchored) {
  BodyId previous = anchored ? test::staticAnchor(chain.world, top) : BodyId{};
  for (int i = 0; i < count; ++i) {
    const Vec3 center = top + direction * (linkLength * (float(i) + 0.5f));
    BodyDef def = test::sphereBody(center, 0.3f * linkLength, linkMass);
    const BodyId link = chain.world.createBody(def);
    if (i > 0 || anchored) {
      chain.joints.push_back(
          chain.world.createBallJoint({previous, link, top + direction * (linkLength * float(i))}));
    }
    chain.links.push_back(link);
    previous = link;
  }
}

float totalGap(const Chain& chain) {
  float total = 0.0f;
  for (const JointId j : chain.joints)
    total += glm::length(chain.world.jointAnchorB(j) - chain.world.jointAnchorA(j));
  return total;
}

TEST(JointTree, FiftyLinkChainReleasedFromTheHorizontalStretchesLessThanOnePercent) {
  Chain chain;
  buildChain(chain, Vec3(0.0f, 10.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 50, 0.1f, 0.1f, true);
  const float length = 5.0f;
  float widest = 0.0f;
  float lowest = 10.0f;
  for (int step = 0; step < 600; ++step) {
    chain.world.step(kDt);
    widest = std::max(widest, totalGap(chain));
    lowest = std::min(lowest, chain.world.transform(chain.links.back()).position.y);
  }
  EXPECT_LT(widest, 0.01f * length);
  EXPECT_LT(lowest, 5.5f);  // it swung down: the tip passed below the anchor by most of the chain
}

TEST(JointTree, AChainOfAlternatingHeavyAndLightLinksGainsNoEnergy) {
  // Ten box links of 0.3 m, 0.1 kg and 100 kg in turn, ball-jointed end to end from a static anchor
  // and released level. A light link's two heavy neighbours pull it round by large and opposite
  // amounts in the projection's Newton steps; turned by each in turn, the chain gained 144 kJ as it
  // swung, ten times what its fall can release (M g L, 14.7 kJ). No step may end with more kinetic
  // and potential energy than the start (the anchor's height is the datum) by 1 % of M g L.
  World world;
  const Vec3 top(0.0f, 10.0f, 0.0f);
  const Vec3 half(0.15f, 0.05f, 0.05f);
  BodyId previous = test::staticAnchor(world, top);
  std::vector<BodyId> links;
  float totalMass = 0.0f;
  for (int i = 0; i < 10; ++i) {
    const float mass = i % 2 == 1 ? 100.0f : 0.1f;
    const BodyId link =
        world.createBody(test::boxBody(top + Vec3(0.3f * float(i) + 0.15f, 0.0f, 0.0f), half, mass));
    world.createBallJoint({previous, link, top + Vec3(0.3f * float(i), 0.0f, 0.0f)});
    links.push_back(link);
    previous = link;
    totalMass += mass;
  }
  const auto energy = [&] {
    double total = world.kineticEnergy();
    for (const BodyId link : links)
      total += world.mass(link) * test::kG * (world.transform(link).position.y - top.y);
    return total;
  };
  double most = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    most = std::max(most, energy());
  }
  EXPECT_LT(most, 0.01 * totalMass * test::kG * 3.0);
  EXPECT_LT(world.transform(links.back()).position.y, top.y - 1.0f);  // it swung down
}

TEST(JointTree, FiftyLinkChainHangingAtRestKeepsItsLength) {
  Chain chain;
  buildChain(chain, Vec3(0.0f, 10.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 50, 0.1f, 0.1f, true);
  for (int step = 0; step < 600; ++step) chain.world.step(kDt);
  EXPECT_LT(totalGap(chain), 1e-4f * 5.0f);
}

// 20 links of 0.1 kg and a 100 kg ball of radius 0.2 m at the end, from a static anchor, released
// at rest along `direction` with the ball at `ballVelocity`. The largest distance of the ball's
// centre from the anchor over 10 s, as a fraction of the chain's length to it.
float heaviestStretch(const Vec3& direction, const Vec3& ballVelocity) {
  Chain chain;
  const Vec3 top(0.0f, 10.0f, 0.0f);
  buildChain(chain, top, direction, 20, 0.1f, 0.1f, true);
  const float radius = 0.2f;
  const float length = 2.0f + radius;
  const BodyId ball = chain.world.createBody(test::sphereBody(top + direction * length, radius, 100.0f));
  chain.world.createBallJoint({chain.links.back(), ball, top + direction * 2.0f});
  chain.world.setLinearVelocity(ball, ballVelocity);
  float widest = 0.0f;
  for (int step = 0; step < 600; ++step) {
    chain.world.step(kDt);
    widest = std::max(widest, glm::length(chain.world.transform(ball).position - top) / length);
  }
  return widest;
}

TEST(JointTree, HeavyBallUnderALightChainStaysWithinTwoPercentOfItsLength) {
  // Gauss-Seidel passes carry the ball's weight up one link per pass: the chain stretched by 68 %.
  EXPECT_LT(heaviestStretch(Vec3(0.0f, -1.0f, 0.0f), Vec3(0.0f)), 1.02f);
  // Swinging, the links carry up to 2000 N: held only with their load's geometric stiffness (without
  // it the links turn further each substep and the chain tears in under a second).
  EXPECT_LT(heaviestStretch(glm::normalize(Vec3(1.0f, -1.0f, 0.0f)), Vec3(0.0f)), 1.02f);
  EXPECT_LT(heaviestStretch(Vec3(0.0f, -1.0f, 0.0f), Vec3(2.0f, 0.0f, 0.5f)), 1.02f);
}

// The same chain and ball made from the ball up, the anchor's joint last: the tree's grounded link
// is its last body. Rooted anywhere but there, the joint below that link cannot move along the
// link (its subtree only turns about the anchor), its pivot is zero and the whole tree falls back
// to the Gauss-Seidel passes, which let the ball sink by far more than 2 %.
TEST(JointTree, ChainBuiltFromItsFreeEndUpIsSolvedAsATree) {
  World world;
  const Vec3 top(0.0f, 10.0f, 0.0f);
  const Vec3 down(0.0f, -1.0f, 0.0f);
  const float radius = 0.2f;
  const float length = 2.0f + radius;
  const BodyId ball = world.createBody(test::sphereBody(top + down * length, radius, 100.0f));
  BodyId below = ball;
  for (int i = 19; i >= 0; --i) {
    const BodyId link =
        world.createBody(test::sphereBody(top + down * (0.1f * (float(i) + 0.5f)), 0.03f, 0.1f));
    world.createBallJoint({link, below, top + down * (0.1f * float(i + 1))});
    below = link;
  }
  world.createBallJoint({test::staticAnchor(world, top), below, top});
  float widest = 0.0f;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    widest = std::max(widest, glm::length(world.transform(ball).position - top) / length);
  }
  EXPECT_LT(widest, 1.02f);
}

TEST(JointTree, TumblingFreeChainKeepsItsMomentum) {
  WorldDef def;
  def.gravity = Vec3(0.0f);
  Chain chain{World(def), {}, {}};
  buildChain(chain, Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), 10, 0.2f, 0.5f, false);
  // Spun about its middle and thrown: the joints' forces are internal.
  for (std::size_t i = 0; i < chain.links.size(); ++i) {
    const Vec3 r = chain.world.transform(chain.links[i]).position - Vec3(1.0f, 0.0f, 0.0f);
    chain.world.setLinearVelocity(chain.links[i],
                                  Vec3(0.5f, 0.0f, 0.0f) + glm::cross(Vec3(0.0f, 2.0f, 1.0f), r));
  }
  const auto momentum = [&] {
    Vec3 p(0.0f);
    for (const BodyId b : chain.links) p += 0.5f * chain.world.linearVelocity(b);
    return p;
  };
  // About the centre of mass: the links are spheres of radius 0.06 m, inertia 2/5 m r^2.
  const auto angularMomentum = [&] {
    Vec3 center(0.0f);
    for (const BodyId b : chain.links)
      center += chain.world.transform(b).position / float(chain.links.size());
    Vec3 l(0.0f);
    const float inertia = 0.4f * 0.5f * 0.06f * 0.06f;
    for (const BodyId b : chain.links) {
      l += glm::cross(chain.world.transform(b).position - center, 0.5f * chain.world.linearVelocity(b)) +
           inertia * chain.world.angularVelocity(b);
    }
    return l;
  };
  const Vec3 before = momentum();
  const Vec3 angularBefore = angularMomentum();
  for (int step = 0; step < 600; ++step) chain.world.step(kDt);
  EXPECT_LT(glm::length(momentum() - before), 1e-3f * glm::length(before));
  EXPECT_LT(glm::length(angularMomentum() - angularBefore), 1e-3f * glm::length(angularBefore));
  EXPECT_LT(totalGap(chain), 0.01f * 2.0f);
}

// Which joints the trees take, by graph counting. A connected group of V bodies hanging from the
// ground by a spanning tree has V tree joints (V + 1 nodes with the ground); its other joints close
// loops. An n x n grid hung by one corner has n^2 tree joints and (n - 1)^2 loops: at n = 8, 64 and
// 49, more loops than half the tree, a mesh, all Gauss-Seidel. A ladder of two 8-body rails with a
// rung at each body, hung by one rail's top, has 16 tree joints and 7 loops: it keeps its tree.
// A chain in the same world keeps its tree beside the mesh.
TEST(JointTree, AGridIsAMeshLeftToGaussSeidelWhileALadderAndAChainKeepTheirTrees) {
  World world;
  constexpr int n = 8;
  const auto ball = [&](const Vec3& at) { return world.createBody(test::sphereBody(at, 0.1f, 1.0f)); };
  const auto countInTree = [&](const std::vector<JointId>& joints) {
    return std::count_if(joints.begin(), joints.end(), [&](JointId j) { return world.jointInTree(j); });
  };

  std::vector<std::vector<BodyId>> grid(n, std::vector<BodyId>(n));
  std::vector<JointId> gridJoints;
  for (int column = 0; column < n; ++column) {
    for (int row = 0; row < n; ++row) {
      const Vec3 at(0.5f * float(column), 20.0f - 0.5f * float(row), 0.0f);
      grid[column][row] = ball(at);
      if (column > 0)
        gridJoints.push_back(
            world.createBallJoint({grid[column - 1][row], grid[column][row], at - Vec3(0.25f, 0, 0)}));
      if (row > 0)
        gridJoints.push_back(
            world.createBallJoint({grid[column][row - 1], grid[column][row], at + Vec3(0, 0.25f, 0)}));
    }
  }
  const Vec3 corner = world.transform(grid[0][0]).position + Vec3(0.0f, 0.25f, 0.0f);
  gridJoints.push_back(world.createBallJoint({test::staticAnchor(world, corner), grid[0][0], corner}));

  std::vector<JointId> ladderJoints;
  BodyId left{}, right{};
  for (int i = 0; i < n; ++i) {
    const Vec3 at(10.0f, 20.0f - 0.5f * float(i), 0.0f);
    const BodyId nextLeft = ball(at);
    const BodyId nextRight = ball(at + Vec3(0.5f, 0.0f, 0.0f));
    const Vec3 railJoint = at + Vec3(0.0f, 0.25f, 0.0f);
    ladderJoints.push_back(
        i == 0 ? world.createBallJoint({test::staticAnchor(world, railJoint), nextLeft, railJoint})
               : world.createBallJoint({left, nextLeft, railJoint}));
    if (i > 0)
      ladderJoints.push_back(world.createBallJoint({right, nextRight, railJoint + Vec3(0.5f, 0.0f, 0.0f)}));
    ladderJoints.push_back(world.createBallJoint({nextLeft, nextRight, at + Vec3(0.25f, 0.0f, 0.0f)}));
    left = nextLeft;
    right = nextRight;
  }

  std::vector<JointId> chainJoints;
  BodyId previous = test::staticAnchor(world, Vec3(-10.0f, 20.0f, 0.0f));
  for (int i = 0; i < 5; ++i) {
    const Vec3 top(-10.0f, 20.0f - 0.5f * float(i), 0.0f);
    const BodyId link = ball(top - Vec3(0.0f, 0.25f, 0.0f));
    chainJoints.push_back(world.createBallJoint({previous, link, top}));
    previous = link;
  }

  // A second of steps: a tree whose factor failed (its rows out of place) leaves its joints for the pass.
  for (int step = 0; step < 60; ++step) world.step(kDt);
  EXPECT_EQ(countInTree(gridJoints), 0);
  EXPECT_EQ(countInTree(ladderJoints), 2 * n);
  EXPECT_EQ(countInTree(chainJoints), 5);
}

}  // namespace
}  // namespace collide
