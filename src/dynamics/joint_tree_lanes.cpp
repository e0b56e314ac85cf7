// The joint trees' four-lane kernels (joint_tree_lanes.h): two SSE2 halves (or plain lanes), or
// AVX registers where the processor has AVX2 (joint_tree_lanes_avx2.cpp).
#include "dynamics/joint_tree_lanes.h"
#include "simd/simd_double.h"

#include <atomic>

namespace collide::detail {

#if COLLIDE_HAVE_AVX2_LANES
const TreeLaneKernels& avx2TreeLaneKernels();
#endif

namespace {
std::atomic<bool> baselineOnly{false};
}  // namespace

void setTreeLanesBaselineOnly(bool only) { baselineOnly.store(only, std::memory_order_relaxed); }

const TreeLaneKernels& treeLaneKernels() {
  static constexpr TreeLaneKernels kBaseline{&lanes::factor<DoubleW4>, &lanes::solve<DoubleW4>};
#if COLLIDE_HAVE_AVX2_LANES
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && !baselineOnly.load(std::memory_order_relaxed)) return avx2TreeLaneKernels();
#endif
  return kBaseline;
}

}  // namespace collide::detail
