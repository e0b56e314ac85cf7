// All four broad-phase algorithms against the brute-force reference on random scenes that change
// over many steps: inserts, removals, small moves, teleports, static updates, layers and masks
// changed. The pair lists (ids and labels) and every query must be exactly equal, and the pairs those
// of a direct test of every two proxies.
#include <collide/broadphase.h>
#include <collide/error.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "support/collide_error.h"

using namespace collide;

namespace {

constexpr std::array<BroadPhaseType, 4> kTypes = {BroadPhaseType::BruteForce, BroadPhaseType::Tree,
                                                  BroadPhaseType::SweepAndPrune, BroadPhaseType::Grid};

// The same proxies in all four broad phases; ids are equal because all allocate slots the same way.
class Scene {
 public:
  // With `masks`, proxies get random pairing masks, and a few change their layer or mask each step.
  explicit Scene(unsigned seed, bool masks = false) : rng_(seed), masks_(masks) {
    for (std::size_t i = 0; i < kTypes.size(); ++i) {
      BroadPhaseSettings settings;
      settings.type = kTypes[i];
      phases_[i] = createBroadPhase(settings);
    }
  }

  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  Aabb randomBox(float halfWorld, float maxHalfSize) {
    const Vec3 c(uniform(-halfWorld, halfWorld), uniform(-halfWorld, halfWorld),
                 uniform(-halfWorld, halfWorld));
    const Vec3 h(uniform(0.05f, maxHalfSize), uniform(0.05f, maxHalfSize), uniform(0.05f, maxHalfSize));
    return Aabb::fromCenterHalfExtents(c, h);
  }

  // No filter, none at all, or a few of the four layers the proxies are on (with a high bit none is).
  LayerMask randomMask() {
    const int roll = integer(0, 5);
    return roll == 0 ? kAllLayers : roll == 1 ? 0u : static_cast<LayerMask>(integer(0, 15)) | 0x100u;
  }
  // One of the four layers, or none (a proxy of layer 0 pairs only through kAllLayers masks).
  std::uint32_t randomLayer() { return integer(0, 9) == 0 ? 0u : 1u << integer(0, 3); }

  ProxyId add(const Aabb& box, MotionType motion) {
    ProxyDef def{box, motion, static_cast<std::uint64_t>(integer(0, 1000)), 1u << integer(0, 3)};
    if (masks_) {
      def.layer = randomLayer();
      def.mask = randomMask();
    }
    ProxyId id;
    for (std::size_t i = 0; i < kTypes.size(); ++i) {
      const ProxyId got = phases_[i]->add(def);
      if (i == 0) id = got;
      EXPECT_EQ(got, id);
    }
    (motion == MotionType::Static ? statics_ : movables_).push_back(id);
    return id;
  }

  void update(ProxyId id, const Aabb& box) {
    for (auto& phase : phases_) phase->update(id, box);
  }
  void remove(std::vector<ProxyId>& list, std::size_t k) {
    for (auto& phase : phases_) phase->remove(list[k]);
    list[k] = list.back();
    list.pop_back();
  }

  // One step of a game: most movables drift a little, a few teleport; some come and go.
  void step() {
    for (const ProxyId id : movables_) {
      const int roll = integer(0, 99);
      if (roll < 60) continue;  // at rest this step
      Aabb box = phases_[0]->bounds(id);
      if (roll < 97) {
        const Vec3 d(uniform(-0.3f, 0.3f), uniform(-0.3f, 0.3f), uniform(-0.3f, 0.3f));
        box = {box.min + d, box.max + d};
      } else {
        box = randomBox(10.0f, 1.0f);
      }
      update(id, box);
    }
    for (int k = integer(0, 4); k > 0 && !movables_.empty(); --k) {
      remove(movables_, static_cast<std::size_t>(integer(0, static_cast<int>(movables_.size()) - 1)));
    }
    for (int k = integer(0, 4); k > 0; --k) add(randomBox(10.0f, 1.0f), MotionType::Movable);
    if (integer(0, 3) == 0 && statics_.size() > 1) {
      remove(statics_, static_cast<std::size_t>(integer(1, static_cast<int>(statics_.size()) - 1)));
      add(randomBox(10.0f, 2.0f), MotionType::Static);
    }
    if (integer(0, 3) == 0 && statics_.size() > 1) update(statics_[1], randomBox(10.0f, 2.0f));
    for (int k = masks_ ? integer(0, 6) : 0; k > 0; --k) {
      std::vector<ProxyId>& list = integer(0, 3) == 0 ? statics_ : movables_;
      if (list.empty()) continue;
      const ProxyId id = list[static_cast<std::size_t>(integer(0, static_cast<int>(list.size()) - 1))];
      const bool layer = integer(0, 1) == 0;
      const std::uint32_t value = layer ? randomLayer() : randomMask();
      for (auto& phase : phases_) layer ? phase->setLayer(id, value) : phase->setMask(id, value);
    }
  }

  // The pairs by a direct test of every two proxies alive: boxes overlapping, not both static, each
  // one's mask kAllLayers or holding the other's layer. Sorted by index.
  Array<ProxyPair> directPairs() const {
    std::vector<ProxyId> ids(statics_);
    ids.insert(ids.end(), movables_.begin(), movables_.end());
    std::sort(ids.begin(), ids.end(), [](ProxyId a, ProxyId b) { return a.index < b.index; });
    const BroadPhase& bp = *phases_[0];
    const auto takes = [&](ProxyId self, ProxyId other) {
      return bp.mask(self) == kAllLayers || (bp.layer(other) & bp.mask(self)) != 0;
    };
    Array<ProxyPair> pairs;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      for (std::size_t j = i + 1; j < ids.size(); ++j) {
        const bool aStatic = bp.motion(ids[i]) == MotionType::Static;
        const bool bStatic = bp.motion(ids[j]) == MotionType::Static;
        if ((aStatic && bStatic) || !bp.bounds(ids[i]).overlaps(bp.bounds(ids[j]))) continue;
        if (!takes(ids[i], ids[j]) || !takes(ids[j], ids[i])) continue;
        pairs.push_back({ids[i], ids[j], aStatic || bStatic ? PairKind::OneWay : PairKind::TwoWay});
      }
    }
    return pairs;
  }

  void populate(int movables, int statics) {
    // A ground slab under everything: the oversize case for the grid, the long box for the sweep.
    add(Aabb{Vec3(-12.0f, -12.0f, -12.0f), Vec3(12.0f, -9.0f, 12.0f)}, MotionType::Static);
    for (int i = 0; i < statics; ++i) add(randomBox(10.0f, 2.0f), MotionType::Static);
    for (int i = 0; i < movables; ++i) add(randomBox(10.0f, 1.0f), MotionType::Movable);
  }

  BroadPhase& phase(std::size_t i) { return *phases_[i]; }
  std::mt19937& rng() { return rng_; }

 private:
  std::mt19937 rng_;
  bool masks_ = false;
  std::array<std::unique_ptr<BroadPhase>, 4> phases_;
  std::vector<ProxyId> movables_;
  std::vector<ProxyId> statics_;
};

std::string name(std::size_t i) { return std::string(toString(kTypes[i])); }

void expectSamePairs(Scene& scene, int step) {
  Array<ProxyPair> reference;
  const BroadPhaseStats referenceStats = scene.phase(0).findPairs(reference);
  const std::uint64_t n = scene.phase(0).proxyCount();
  EXPECT_EQ(referenceStats.potentialPairs, n * (n - 1) / 2);
  EXPECT_EQ(referenceStats.keptPairs, reference.size());
  ASSERT_FALSE(reference.empty()) << "the scene should have some overlaps";
  for (const ProxyPair& p : reference) {
    const BroadPhase& bp = scene.phase(0);
    ASSERT_LT(p.a.index, p.b.index);
    ASSERT_TRUE(bp.bounds(p.a).overlaps(bp.bounds(p.b)));
    const bool aStatic = bp.motion(p.a) == MotionType::Static, bStatic = bp.motion(p.b) == MotionType::Static;
    ASSERT_FALSE(aStatic && bStatic) << "static-static pair produced";
    ASSERT_EQ(p.kind, aStatic || bStatic ? PairKind::OneWay : PairKind::TwoWay);
  }
  ASSERT_TRUE(reference == scene.directPairs()) << "brute force at step " << step;
  for (std::size_t i = 1; i < kTypes.size(); ++i) {
    Array<ProxyPair> pairs;
    const BroadPhaseStats stats = scene.phase(i).findPairs(pairs);
    EXPECT_EQ(stats.potentialPairs, referenceStats.potentialPairs);
    ASSERT_EQ(pairs.size(), reference.size()) << name(i) << " at step " << step;
    ASSERT_TRUE(pairs == reference) << name(i) << " at step " << step;
    scene.phase(i).validate();
  }
}

}  // namespace

TEST(BroadPhaseEquivalence, PairsEqualBruteForceThroughRandomEdits) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    Scene scene(seed);
    scene.populate(250, 60);
    for (int step = 0; step < 40; ++step) {
      expectSamePairs(scene, step);
      if (HasFatalFailure()) return;
      scene.step();
    }
  }
}

// Masks that leave pairs out, layers and masks changed between steps: the tree skips subtrees by
// its nodes' layer unions and finds again the pairs a change lets in.
TEST(BroadPhaseEquivalence, PairsFollowLayersAndMasksThroughRandomEdits) {
  for (unsigned seed : {5u, 6u, 7u}) {
    Scene scene(seed, true);
    scene.populate(250, 60);
    for (int step = 0; step < 40; ++step) {
      expectSamePairs(scene, step);
      if (HasFatalFailure()) return;
      scene.step();
    }
  }
}

TEST(BroadPhaseEquivalence, BruteForceKeepsOnlyATinyFractionOfPotentialPairs) {
  // The lecture's point, measured: a scene of a few hundred sparse objects keeps well under 1% of
  // the n(n-1)/2 potential pairs.
  Scene scene(7);
  scene.populate(300, 0);
  Array<ProxyPair> pairs;
  const BroadPhaseStats stats = scene.phase(0).findPairs(pairs);
  EXPECT_EQ(stats.potentialPairs, 301u * 300u / 2u);
  EXPECT_LT(stats.keptFraction(), 0.01);
  EXPECT_GT(stats.keptFraction(), 0.0);
}

TEST(BroadPhaseEquivalence, QueriesEqualBruteForce) {
  for (unsigned seed : {11u, 12u, 13u}) {
    Scene scene(seed);
    scene.populate(250, 60);
    for (int round = 0; round < 3; ++round) {
      // Queries are asked both right after edits and after a findPairs.
      if (round == 1) {
        Array<ProxyPair> pairs;
        for (std::size_t i = 0; i < kTypes.size(); ++i) scene.phase(i).findPairs(pairs);
      }
      for (int q = 0; q < 40; ++q) {
        const Vec3 origin(scene.uniform(-15.0f, 15.0f), scene.uniform(-15.0f, 15.0f),
                          scene.uniform(-15.0f, 15.0f));
        Vec3 direction(scene.uniform(-1.0f, 1.0f), scene.uniform(-1.0f, 1.0f), scene.uniform(-1.0f, 1.0f));
        if (q % 8 == 0) direction = Vec3(0.0f, 0.0f, q % 16 == 0 ? 1.0f : -1.0f);  // axis-parallel rays
        const Ray ray{origin, glm::normalize(direction), q % 2 == 0 ? 1e30f : scene.uniform(1.0f, 20.0f)};
        const LayerMask mask = q % 3 == 0 ? kAllLayers : static_cast<LayerMask>(scene.integer(1, 15));
        const Aabb box = scene.randomBox(12.0f, 3.0f);
        const BoundingSphere sphere{box.center(), scene.uniform(0.0f, 4.0f)};
        const Vec3 target(scene.uniform(-15.0f, 15.0f), scene.uniform(-15.0f, 15.0f),
                          scene.uniform(-15.0f, 15.0f));
        const Vec3 eye(scene.uniform(-20.0f, 20.0f), scene.uniform(-20.0f, 20.0f),
                       scene.uniform(-20.0f, 20.0f));
        const Mat4 viewProjection = glm::perspective(glm::radians(scene.uniform(20.0f, 90.0f)), 1.5f, 0.5f,
                                                     scene.uniform(5.0f, 40.0f)) *
                                    glm::lookAt(eye, target, Vec3(0.0f, 1.0f, 0.0f));
        const Frustum frustum = Frustum::fromViewProjection(viewProjection);

        const BroadPhase& reference = scene.phase(0);
        const auto closest = reference.rayCastClosest(ray, mask);
        const auto all = reference.rayCastAll(ray, mask);
        const auto inBox = reference.overlapAabb(box, mask);
        // By motion type: the proxies of the full query of that type, in the same order.
        const auto inBoxBy = [&](const BroadPhase& bp, MotionFilter motions) {
          std::vector<ProxyId> found;
          bp.queryAabb(box, mask, motions, [&](ProxyId id) {
            found.push_back(id);
            return true;
          });
          std::sort(found.begin(), found.end(), [](ProxyId x, ProxyId y) { return x.index < y.index; });
          return found;
        };
        std::vector<ProxyId> inBoxStatic, inBoxMovable;
        for (const ProxyId id : inBox)
          (reference.motion(id) == MotionType::Static ? inBoxStatic : inBoxMovable).push_back(id);
        EXPECT_EQ(inBoxBy(reference, MotionFilter::StaticOnly), inBoxStatic);
        EXPECT_EQ(inBoxBy(reference, MotionFilter::MovableOnly), inBoxMovable);
        EXPECT_EQ(inBoxBy(reference, MotionFilter::All), inBox);
        const auto inSphere = reference.overlapSphere(sphere, mask);
        const auto inFrustum = reference.cullFrustum(frustum, mask);
        const bool blocked = reference.isSegmentBlocked(origin, target, mask);
        for (std::size_t i = 1; i < kTypes.size(); ++i) {
          const BroadPhase& bp = scene.phase(i);
          const auto c = bp.rayCastClosest(ray, mask);
          ASSERT_EQ(c.has_value(), closest.has_value()) << name(i);
          if (c) {
            EXPECT_EQ(c->id, closest->id) << name(i);
            EXPECT_EQ(c->distance, closest->distance) << name(i);
          }
          const auto a = bp.rayCastAll(ray, mask);
          ASSERT_EQ(a.size(), all.size()) << name(i);
          for (std::size_t k = 0; k < a.size(); ++k) {
            EXPECT_EQ(a[k].id, all[k].id) << name(i);
            EXPECT_EQ(a[k].distance, all[k].distance) << name(i);
          }
          EXPECT_EQ(bp.overlapAabb(box, mask), inBox) << name(i);
          EXPECT_EQ(inBoxBy(bp, MotionFilter::StaticOnly), inBoxStatic) << name(i);
          EXPECT_EQ(inBoxBy(bp, MotionFilter::MovableOnly), inBoxMovable) << name(i);
          EXPECT_EQ(bp.overlapSphere(sphere, mask), inSphere) << name(i);
          EXPECT_EQ(bp.cullFrustum(frustum, mask), inFrustum) << name(i);
          EXPECT_EQ(bp.isSegmentBlocked(origin, target, mask), blocked) << name(i);
        }
        if (HasFailure()) return;
      }
      scene.step();
    }
  }
}

TEST(BroadPhaseEquivalence, BruteForceQueriesAgreeWithDirectTests) {
  // The reference itself, checked against the per-box tests written out here.
  Scene scene(21);
  scene.populate(100, 20);
  const BroadPhase& bp = scene.phase(0);
  const Aabb box{Vec3(-3.0f), Vec3(4.0f)};
  const auto found = bp.overlapAabb(box);
  std::size_t expected = 0;
  for (std::uint32_t i = 0; i < bp.records().size(); ++i) {
    const auto& r = bp.records()[i];
    if (r.alive && r.bounds.overlaps(box)) ++expected;
  }
  EXPECT_EQ(found.size(), expected);
  const Ray ray{Vec3(-20.0f, 0.1f, 0.2f), Vec3(1.0f, 0.0f, 0.0f), 1e30f};
  const auto hits = bp.rayCastAll(ray);
  for (const ProxyRayHit& hit : hits) EXPECT_GE(rayAabbEntry(ray, bp.bounds(hit.id)), 0.0f);
  for (std::size_t k = 1; k < hits.size(); ++k) EXPECT_LE(hits[k - 1].distance, hits[k].distance);
}

namespace {

// A box cast written out: whether the box, moved along `translation` in 2,000 even steps, overlaps
// `target` at one of them (the tests ask it only of clear cases: boxes grown or shrunk by 1 mm).
bool movingBoxTouches(const Aabb& box, const Vec3& translation, const Aabb& target) {
  for (int k = 0; k <= 2000; ++k) {
    const Vec3 d = translation * (float(k) / 2000.0f);
    if (Aabb{box.min + d, box.max + d}.overlaps(target)) return true;
  }
  return false;
}

}  // namespace

TEST(BroadPhaseEquivalence, BoxCastsEqualEveryAlgorithmAndTheWrittenOutTest) {
  // Every algorithm hands out the same proxies at the same distances; the reference's proxies are
  // those a finely sampled moving box touches, and the distances are where the box first touches.
  Scene scene(31);
  scene.populate(200, 40);
  int reported = 0;
  for (int q = 0; q < 60; ++q) {
    const Aabb box = scene.randomBox(12.0f, 1.0f);
    Vec3 translation(scene.uniform(-15.0f, 15.0f), scene.uniform(-15.0f, 15.0f),
                     scene.uniform(-15.0f, 15.0f));
    if (q % 10 == 0) translation = Vec3(0.0f, 0.0f, scene.uniform(-15.0f, 15.0f));  // along an axis
    if (q % 20 == 0) translation = Vec3(0.0f);                                      // an overlap query
    const auto cast = [&](const BroadPhase& bp) {
      std::vector<std::pair<std::uint32_t, float>> hits;
      bp.boxCast(box, translation, kAllLayers, [&](ProxyId id, float distance) {
        hits.push_back({id.index, distance});
        return std::numeric_limits<float>::infinity();
      });
      std::sort(hits.begin(), hits.end());
      return hits;
    };
    const auto reference = cast(scene.phase(0));
    for (std::size_t i = 1; i < kTypes.size(); ++i)
      EXPECT_EQ(cast(scene.phase(i)), reference) << name(i) << " cast " << q;
    const BroadPhase& bp = scene.phase(0);
    const float length = glm::length(translation);
    for (const auto& [index, distance] : reference) {
      const Aabb target = bp.records()[index].bounds;
      EXPECT_TRUE(movingBoxTouches(box, translation, target.expanded(1e-3f))) << "cast " << q;
      if (length > 0.0f) {
        // Just before the reported distance the box is clear of the target (unless it starts touching).
        const Vec3 before = translation * (std::max(0.0f, distance - 1e-3f) / length);
        if (distance > 1e-3f) {
          EXPECT_FALSE((Aabb{box.min + before, box.max + before}.overlaps(target))) << "cast " << q;
        }
        const Vec3 at = translation * (distance / length);
        EXPECT_TRUE((Aabb{box.min + at, box.max + at}.expanded(1e-3f).overlaps(target))) << "cast " << q;
      }
    }
    // Every proxy the sampled box clearly touches is reported.
    for (std::uint32_t index = 0; index < bp.records().size(); ++index) {
      const auto& r = bp.records()[index];
      if (!r.alive || !movingBoxTouches(box.expanded(-1e-3f), translation, r.bounds)) continue;
      EXPECT_TRUE(
          std::any_of(reference.begin(), reference.end(), [&](const auto& h) { return h.first == index; }))
          << "cast " << q << " proxy " << index;
    }
    reported += static_cast<int>(reference.size());
    if (HasFailure()) return;
  }
  EXPECT_GT(reported, 100);
  EXPECT_COLLIDE_ERROR(scene.phase(0).boxCast(Aabb{Vec3(NAN), Vec3(0.0f)}, Vec3(1.0f), kAllLayers,
                                              [](ProxyId, float) { return 0.0f; }));
}
