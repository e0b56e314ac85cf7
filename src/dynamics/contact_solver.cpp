// The soft-step contact solver: batches, warm start, solve, restitution, store (contact_solver.h).
#include "dynamics/contact_solver.h"
#include "base/fail.h"

#include "dynamics/constraint_graph.h"
#include "dynamics/contact_lanes.h"
#include "memory/heap_bytes.h"
#include "memory/prefetch.h"

#include <collide/error.h>

#include <algorithm>
#include <string>

namespace collide::detail {

#if COLLIDE_HAVE_AVX2_LANES
// contact_solver_avx2.cpp, built with AVX2 enabled; run only where the processor has it.
std::unique_ptr<ContactLanes> makeAvx2ContactLanes();
#endif

Softness makeSoftness(float hertz, float dampingRatio, float h) {
  if (hertz == 0.0f) return {0.0f, 1.0f, 0.0f};
  const float omega = 2.0f * kPi * hertz;
  const float a1 = 2.0f * dampingRatio + h * omega;
  const float a2 = h * omega * a1;
  const float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3, a3};
}

int widestContactLanes() {
#if COLLIDE_HAVE_AVX2_LANES
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return 8;
#endif
  return 4;
}

namespace {
int defaultLaneWidth = 0;
}  // namespace

void setDefaultContactLanes(int laneWidth) { defaultLaneWidth = laneWidth; }

ContactSolver::ContactSolver(int laneWidth) {
  if (laneWidth == 0) laneWidth = defaultLaneWidth;
  if (laneWidth == 0) laneWidth = widestContactLanes();
  if (laneWidth == 4) {
    lanes_ = std::make_unique<LaneContactSolver<FloatW>>();
#if COLLIDE_HAVE_AVX2_LANES
  } else if (laneWidth == 8 && widestContactLanes() == 8) {
    lanes_ = makeAvx2ContactLanes();
#endif
  } else {
    // Without exceptions the four-lane kernel, which every x86-64 has, stands in.
    lanes_ = std::make_unique<LaneContactSolver<FloatW>>();
    COLLIDE_FAIL("contact solver: lane width " + std::to_string(laneWidth) + " is not available here (4" +
                 std::string(widestContactLanes() == 8 ? " or 8" : "") + ")");
  }
}

ContactSolver::~ContactSolver() = default;
ContactSolver::ContactSolver(ContactSolver&&) noexcept = default;
ContactSolver& ContactSolver::operator=(ContactSolver&&) noexcept = default;

void ContactSolver::prepare(Array<Contact>& contacts, const BodyStorage& storage,
                            const Array<SolverBody>& bodies, const Array<SolverBodyInfo>& infos,
                            const Array<std::int32_t>& solverOf, const ContactSolverSettings& settings,
                            SolverBlocks* blocks, float h, TaskRunner& tasks) {
  // The contacts to solve and the solver bodies each may write.
  solvedContacts_.clear();
  writtenBodies_.clear();
  blockOf_.clear();
  pointCounts_.clear();
  bool unequalMasses = false;
  for (std::uint32_t ci = 0; ci < contacts.size(); ++ci) {
    // The lines read here (ids, manifold count, flags) a few contacts ahead: a contact spans several
    // cache lines, a stride the hardware's prefetcher does not follow in time.
    if (ci + 8 < contacts.size()) {
      const Contact& ahead = contacts[ci + 8];
      prefetchLine(&ahead.manifold.count);
      prefetchLine(&ahead.sensor);
    }
    const Contact& contact = contacts[ci];
    if (contact.sensor || !contact.enabled || contact.asleep || contact.manifold.count == 0) continue;
    const std::int32_t a = solverOf[contact.bodyA];
    const std::int32_t b = solverOf[contact.bodyB];
    solvedContacts_.push_back(ci);
    pointCounts_.push_back(static_cast<std::uint8_t>(contact.manifold.count));
    // It joins its bodies' islands; its block is that of a side in the solve (kept here, found
    // once the islands are known).
    if (blocks != nullptr) {
      blocks->join(a, b);
      blockOf_.push_back(static_cast<std::uint32_t>(a >= 0 ? a : b));
    }
    const std::int32_t writtenA = a >= 0 && infos[a].dynamic ? a : kNoSolverBody;
    const std::int32_t writtenB = b >= 0 && infos[b].dynamic ? b : kNoSolverBody;
    writtenBodies_.push_back({writtenA, writtenB});
    unequalMasses = unequalMasses || (writtenA != kNoSolverBody && writtenB != kNoSolverBody &&
                                      infos[writtenA].inverseMass != infos[writtenB].inverseMass);
  }
  if (blocks != nullptr) {
    blocks->finish();
    for (std::uint32_t& side : blockOf_)
      side = side == static_cast<std::uint32_t>(kNoSolverBody) ? 0 : blocks->blockOf(side);
  }
  colorConstraints(writtenBodies_, bodies.size(), colorOf_, colorBits_);
  // Support masses need a body resting on a lighter one: none where every contact between two
  // dynamic bodies joins equal masses (a pile of equal boxes), and their scan of the contacts is
  // skipped.
  if (settings.tuning.supportMasses && unequalMasses) {
    supportMasses_.compute(contacts, solvedContacts_, solverOf, infos, bodies, storage, settings.gravity,
                           settings.tuning.restitutionThreshold);
  } else {
    supportMasses_.clear();
  }

  // By block, then by colour within the block, the overflow last. Within a colour the contacts
  // share no body that moves, so their order changes no result: they go by point count, most
  // first, so that a batch's lanes have as many points as each other and the solver loops over (and
  // loads) no point slot that all its lanes leave empty. The overflow colour is solved one contact
  // after another and keeps the contact order, as does each body's sequence of contacts: its
  // island's are all in its block. A counting sort, stable (determinism).
  constexpr std::uint32_t kCounts = Manifold::kMaxPoints;
  const std::uint32_t blockCount = blocks != nullptr ? blocks->count() : 1;
  const auto bucketOf = [&](std::size_t i) {
    const std::uint32_t color = colorOf_[i];
    const std::uint32_t count = pointCounts_[i];
    const std::uint32_t block = blocks != nullptr ? blockOf_[i] : 0;
    return (block * kColorSegments + color) * kCounts + (color == kOverflowColor ? 0 : kCounts - count);
  };
  const std::uint32_t segments = blockCount * kColorSegments;
  bucketStart_.assign(segments * kCounts + 1, 0);
  for (std::size_t i = 0; i < solvedContacts_.size(); ++i) ++bucketStart_[bucketOf(i) + 1];
  for (std::size_t k = 1; k < bucketStart_.size(); ++k) bucketStart_[k] += bucketStart_[k - 1];
  countStart_ = bucketStart_;
  order_.resize(solvedContacts_.size());
  for (std::size_t i = 0; i < solvedContacts_.size(); ++i)
    order_[bucketStart_[bucketOf(i)]++] = solvedContacts_[i];
  solvedContacts_.swap(order_);

  // Every spring is capped at a quarter of the substep rate (h omega <= pi / 2), where Gauss-Seidel
  // still resolves it; stiffer, coupled points overshoot and stacks shiver (docs/architecture.md).
  const float maxHertz = kMaxHertzPerSubstepRate / h;
  const ContactTuning& tuning = settings.tuning;
  const ContactBatchInput input{
      contacts, solvedContacts_, blockCount, countStart_, storage, bodies, infos, solverOf,
      makeSoftness(std::min(tuning.hertz, maxHertz), tuning.dampingRatio, h),
      // A one-way pair has half the effective mass to move: Box2D v3 doubles its stiffness, within the cap.
      makeSoftness(std::min(2.0f * tuning.hertz, maxHertz), tuning.dampingRatio, h), settings.friction,
      tuning.frictionAnchorReach, tuning.pushOutSpeed, tuning.restitutionThreshold,
      supportMasses_.empty() ? nullptr : &supportMasses_};
  lanes_->build(input, tasks);
}

std::size_t ContactSolver::memoryBytes() const {
  return lanes_->memoryBytes() + supportMasses_.memoryBytes() + heapBytes(solvedContacts_) +
         heapBytes(writtenBodies_) + heapBytes(colorBits_) + heapBytes(order_) + heapBytes(colorOf_) +
         heapBytes(blockOf_) + heapBytes(pointCounts_) + heapBytes(bucketStart_) + heapBytes(countStart_);
}

}  // namespace collide::detail
