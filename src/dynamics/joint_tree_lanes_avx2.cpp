// The joint trees' four-lane kernels in AVX registers (joint_tree_lanes.h), compiled with AVX2 and
// without FMA; chosen at run time where the processor has AVX2.
#include "dynamics/joint_tree_lanes.h"
#include "simd/simd_double_avx.h"

namespace collide::detail {

const TreeLaneKernels& avx2TreeLaneKernels() {
  static constexpr TreeLaneKernels kernels{&lanes::factor<DoubleW4Avx>, &lanes::solve<DoubleW4Avx>};
  return kernels;
}

}  // namespace collide::detail
