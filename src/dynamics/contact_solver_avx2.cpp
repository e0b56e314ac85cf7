// The contact solver's kernels eight lanes wide. This file alone is compiled with AVX2 (and not FMA,
// which would change the results); ContactSolver picks it at run time where the processor has AVX2
// (widestContactLanes). The kernels are those of contact_lanes.h, as for four lanes.
#include "dynamics/contact_lanes.h"
#include "simd/simd_avx2.h"

namespace collide::detail {

std::unique_ptr<ContactLanes> makeAvx2ContactLanes() {
  return std::make_unique<LaneContactSolver<FloatW8>>();
}

}  // namespace collide::detail
