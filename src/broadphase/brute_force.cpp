// The n² reference: every pair and every query tests every proxy. It is the ground truth the other
// three algorithms are tested against, and honestly the fastest choice for a handful of proxies.
#include "broadphase/broad_phase_internal.h"

namespace collide {

namespace {

class BruteForceBroadPhase final : public LinearScanBroadPhase {
 public:
  explicit BruteForceBroadPhase(const BroadPhaseSettings& settings) : LinearScanBroadPhase(settings) {}

 private:
  void onAdd(std::uint32_t) override {}
  void onRemove(std::uint32_t) override {}
  void onUpdate(std::uint32_t, const Aabb&) override {}

  std::size_t algorithmMemoryBytes() const override { return 0; }  // nothing beyond the records

  bool findPairKeys(Array<std::uint64_t>& outKeys, std::uint64_t& outBoxTests) override {
    const auto count = static_cast<std::uint32_t>(proxies_.size());
    for (std::uint32_t a = 0; a < count; ++a) {
      const ProxyRecord& pa = proxies_[a];
      if (!pa.alive) continue;
      for (std::uint32_t b = a + 1; b < count; ++b) {
        const ProxyRecord& pb = proxies_[b];
        if (!pb.alive) continue;
        if (pa.motion == MotionType::Static && pb.motion == MotionType::Static) continue;
        ++outBoxTests;
        if (pa.bounds.overlaps(pb.bounds)) outKeys.push_back(pairKey(a, b));
      }
    }
    return true;  // generated in (a, b) order
  }
};

}  // namespace

std::unique_ptr<BroadPhase> makeBruteForceBroadPhase(const BroadPhaseSettings& settings) {
  return std::make_unique<BruteForceBroadPhase>(settings);
}

}  // namespace collide
