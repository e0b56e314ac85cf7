// Graph colouring of the constraints for the batched solver (constraint_graph.h).
#include "dynamics/constraint_graph.h"
#include "base/assert.h"

namespace collide::detail {

void colorConstraints(const Array<std::array<std::int32_t, 2>>& writtenBodies, std::size_t bodyCount,
                      Array<std::uint8_t>& outColors, Array<std::uint64_t>& bits) {
  const std::size_t words = (bodyCount + 63) / 64;
  bits.assign(words * kGraphColors, 0);
  outColors.resize(writtenBodies.size());
  const auto used = [&](int color, std::int32_t body) {
    return body >= 0 && (bits[color * words + body / 64] >> (body % 64)) & 1u;
  };
  const auto take = [&](int color, std::int32_t body) {
    if (body >= 0) bits[color * words + body / 64] |= std::uint64_t{1} << (body % 64);
  };
  for (std::size_t i = 0; i < writtenBodies.size(); ++i) {
    const auto [a, b] = writtenBodies[i];
    COLLIDE_ASSERT(a < static_cast<std::int64_t>(bodyCount) && b < static_cast<std::int64_t>(bodyCount));
    COLLIDE_ASSERT(a != b || a < 0);  // a constraint joins two bodies
    const int first = (a < 0 || b < 0) ? 1 : 0;
    std::uint8_t color = kOverflowColor;
    for (int c = first; c < kGraphColors; ++c) {
      if (used(c, a) || used(c, b)) continue;
      take(c, a);
      take(c, b);
      color = static_cast<std::uint8_t>(c);
      break;
    }
    outColors[i] = color;
  }
}

}  // namespace collide::detail
