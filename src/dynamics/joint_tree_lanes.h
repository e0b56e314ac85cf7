// The joint trees' factor and solve for four trees of one shape at once, a tree per double lane
// (joint_tree.h). A pile of ragdolls is a hundred trees of the same nodes: their blocks are small
// (6 for a body, 3 to 8 rows for a joint), and one tree's arithmetic is a chain of dependent
// operations that keeps a core's floating-point units mostly idle. Four trees side by side fill them.
//
// Each lane does what the scalar kernels of joint_tree.cpp do for its tree, operation for operation
// in the same order, so its result is the scalar one bit for bit. A node's blocks are laid out at
// the largest of the four trees' sizes this pass (their limits differ); a tree's rows beyond its own
// size are padding, which the kernels leave out of every sum (masked by the lane's size), and
// whose pivots are 1.
//
// The kernels are templates over the lane type (simd_double.h): DoubleW4 everywhere, DoubleW4Avx
// where the processor has AVX (joint_tree_lanes_avx2.cpp), with the same results.
#pragma once

#include "dynamics/joints/joint_rows.h"

#include <cstddef>
#include <cstdint>

namespace collide::detail {

// Trees per group: the lanes of the kernels' lane types.
inline constexpr std::uint32_t kTreeLanes = 4;
// Unknowns of a node at most (joint_tree.h's kMaxNodeSize).
inline constexpr int kTreeLaneMaxNodeSize = 6 + kMaxJointTreeRows;

// One node of a group of trees: where its blocks lie among the group's lane records (four doubles,
// one per tree), its size this pass (the largest of the trees') and each tree's own.
struct LaneNode {
  std::int32_t parent = -1;          // index among the group's nodes, -1 for the root
  int size = 0;                      // padded: the most unknowns of the four trees' node
  double laneSize[kTreeLanes] = {};  // each tree's unknowns (as doubles, compared in lanes)
  std::uint32_t matrix = 0;          // D (size x size, row-major), in lane records
  std::uint32_t coupling = 0;        // H(node, parent) (size x the parent's size)
  std::uint32_t vector = 0;          // the node's unknowns
};

struct TreeLaneKernels {
  // The block LDL^T of the group's nodes, leaves first (JointTree::factorTree per lane). Returns a
  // bit per lane: its tree factored.
  unsigned (*factor)(const LaneNode* nodes, std::size_t count, double* matrices);
  // The solution in place of the right-hand side, by the factor (JointTree::solveTree per lane).
  void (*solve)(const LaneNode* nodes, std::size_t count, const double* matrices, double* vectors);
};

// The kernels for this processor: AVX where it has it, else two SSE2 halves (or plain lanes).
const TreeLaneKernels& treeLaneKernels();

// For tests (tree lanes are on by default, and AVX where the processor has it): whether the solve
// passes group trees, whether the kernels are the baseline ones even where AVX2 runs, and how many
// groups the last step's trees made.
void setTreeLanes(bool enabled);
void setTreeLanesBaselineOnly(bool baselineOnly);
std::uint32_t lastTreeLaneGroups();

namespace lanes {

// Lane record e of a block: its four doubles.
inline double* at(double* base, std::uint32_t offset, int e) {
  return base + (std::size_t{offset} + e) * kTreeLanes;
}
inline const double* at(const double* base, std::uint32_t offset, int e) {
  return base + (std::size_t{offset} + e) * kTreeLanes;
}

// A size known at compile time (kN > 0), which the compiler unrolls loops over, or at run time.
template <int kN>
int fixedOr(int n) {
  return kN > 0 ? kN : n;
}

// The lanes whose tree has each unknown of the node, for i < size.
template <typename D>
void unknownMasks(const LaneNode& node, int size, D* masks) {
  const D sizes = D::load(node.laneSize);
  for (int i = 0; i < size; ++i) masks[i] = greaterD(sizes, D::splat(double(i)));
}

// factorLdl of joint_tree.cpp per lane: false (its bit clear) where a pivot falls below the
// relative tolerance. Padding rows get pivot 1.
template <typename D, int kN>
D factorLdl(double* blocks, const LaneNode& node, const D* rows) {
  const int n = fixedOr<kN>(node.size);
  const auto a = [&](int r, int c) { return at(blocks, node.matrix, r * n + c); };
  D scale = D::splat(0.0);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k <= i; ++k) scale = maxD(absD(D::load(a(i, k))), scale);
  }
  // scale > 0 and finite (scale is not negative: below infinity, NaN fails).
  D ok = andD(greaterD(scale, D::splat(0.0)), lessD(scale, D::splat(INFINITY)));
  const D tolerance = D::splat(1e-12) * scale;
  const D one = D::splat(1.0);
  D ld[kTreeLaneMaxNodeSize];
  for (int j = 0; j < n; ++j) {
    D pivot = D::load(a(j, j));
    for (int k = 0; k < j; ++k) {
      const D ljk = D::load(a(j, k));
      ld[k] = ljk * D::load(a(k, k));
      pivot = pivot - ljk * ld[k];
    }
    ok = selectD(rows[j], andD(ok, greaterD(absD(pivot), tolerance)), ok);
    pivot = selectD(rows[j], pivot, one);
    store(a(j, j), pivot);
    const D inversePivot = one / pivot;
    for (int i = j + 1; i < n; ++i) {
      D sum = D::load(a(i, j));
      for (int k = 0; k < j; ++k) sum = sum - D::load(a(i, k)) * ld[k];
      store(a(i, j), sum * inversePivot);
    }
  }
  return ok;
}

// x = L^-1 x for the n x cols block x, skipping zero entries of L as the scalar kernel does.
template <typename D, int kN, int kC>
void forwardSubstitute(const double* blocks, const LaneNode& node, const D* rows, double* xBase,
                       std::uint32_t x, int columns) {
  const int n = fixedOr<kN>(node.size);
  const int cols = fixedOr<kC>(columns);
  for (int i = 1; i < n; ++i) {
    for (int k = 0; k < i; ++k) {
      const D l = D::load(at(blocks, node.matrix, i * n + k));
      const D take = andD(rows[i], notEqualD(l, D::splat(0.0)));
      if (maskBits(take) == 0) continue;
      for (int c = 0; c < cols; ++c) {
        double* xi = at(xBase, x, i * cols + c);
        const D value = D::load(xi);
        store(xi, selectD(take, value - l * D::load(at(xBase, x, k * cols + c)), value));
      }
    }
  }
}

// One node's elimination: its D factored, its coupling turned into L^-1 H, the parent's D less
// Y^T D^-1 Y (its lower triangle). The lanes whose factor held.
template <typename D, int kN, int kC>
D eliminateNode(double* matrices, const LaneNode& node, const LaneNode* parent) {
  D rows[kTreeLaneMaxNodeSize];
  const int n = fixedOr<kN>(node.size);
  unknownMasks(node, n, rows);
  const D ok = factorLdl<D, kN>(matrices, node, rows);
  if (parent == nullptr) return ok;
  const int cols = fixedOr<kC>(parent->size);
  D parentRows[kTreeLaneMaxNodeSize];
  unknownMasks(*parent, cols, parentRows);
  forwardSubstitute<D, kN, kC>(matrices, node, rows, matrices, node.coupling, cols);
  for (int k = 0; k < n; ++k) {
    const D inversePivot = D::splat(1.0) / D::load(at(matrices, node.matrix, k * n + k));
    for (int r = 0; r < cols; ++r) {
      const D scaled = D::load(at(matrices, node.coupling, k * cols + r)) * inversePivot;
      const D take = andD(andD(rows[k], parentRows[r]), notEqualD(scaled, D::splat(0.0)));
      if (maskBits(take) == 0) continue;
      for (int c = 0; c <= r; ++c) {
        double* p = at(matrices, parent->matrix, r * cols + c);
        const D value = D::load(p);
        store(p, selectD(take, value - scaled * D::load(at(matrices, node.coupling, k * cols + c)), value));
      }
    }
  }
  return ok;
}

// The solve's way down at one node (leaves first): u = D^-1 L^-1 z, z_parent -= Y^T u.
template <typename D, int kN, int kC>
void solveNodeDown(const double* matrices, const LaneNode& node, const LaneNode* parent, double* vectors) {
  D rows[kTreeLaneMaxNodeSize];
  const int n = fixedOr<kN>(node.size);
  unknownMasks(node, n, rows);
  forwardSubstitute<D, kN, 1>(matrices, node, rows, vectors, node.vector, 1);
  for (int k = 0; k < n; ++k) {
    double* z = at(vectors, node.vector, k);
    store(z, D::load(z) / D::load(at(matrices, node.matrix, k * n + k)));
  }
  if (parent == nullptr) return;
  const int cols = fixedOr<kC>(parent->size);
  for (int k = 0; k < n; ++k) {
    const D zk = D::load(at(vectors, node.vector, k));
    for (int c = 0; c < cols; ++c) {
      double* p = at(vectors, parent->vector, c);
      const D value = D::load(p);
      store(p, selectD(rows[k], value - D::load(at(matrices, node.coupling, k * cols + c)) * zk, value));
    }
  }
}

// The way back at one node (from the root): x = L^-T (u - D^-1 Y x_parent).
template <typename D, int kN, int kC>
void solveNodeUp(const double* matrices, const LaneNode& node, const LaneNode* parent, double* vectors) {
  D rows[kTreeLaneMaxNodeSize];
  const int n = fixedOr<kN>(node.size);
  unknownMasks(node, n, rows);
  if (parent != nullptr) {
    const int cols = fixedOr<kC>(parent->size);
    D parentRows[kTreeLaneMaxNodeSize];
    unknownMasks(*parent, cols, parentRows);
    for (int r = 0; r < n; ++r) {
      D sum = D::splat(0.0);
      for (int k = 0; k < cols; ++k) {
        const D term =
            D::load(at(matrices, node.coupling, r * cols + k)) * D::load(at(vectors, parent->vector, k));
        sum = selectD(parentRows[k], sum + term, sum);
      }
      double* x = at(vectors, node.vector, r);
      store(x, D::load(x) - sum / D::load(at(matrices, node.matrix, r * n + r)));
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    double* x = at(vectors, node.vector, i);
    D sum = D::load(x);
    for (int k = i + 1; k < n; ++k) {
      const D term = D::load(at(matrices, node.matrix, k * n + i)) * D::load(at(vectors, node.vector, k));
      sum = selectD(rows[k], sum - term, sum);
    }
    store(x, sum);
  }
}

// The instances for a node of this size under a parent of that size, as joint_tree.cpp picks them.
template <typename D>
struct NodeKernels {
  D (*eliminate)(double*, const LaneNode&, const LaneNode*);
  void (*down)(const double*, const LaneNode&, const LaneNode*, double*);
  void (*up)(const double*, const LaneNode&, const LaneNode*, double*);
};
template <typename D, int kN, int kC>
constexpr NodeKernels<D> kernelsFor() {
  return {&eliminateNode<D, kN, kC>, &solveNodeDown<D, kN, kC>, &solveNodeUp<D, kN, kC>};
}
template <typename D>
NodeKernels<D> nodeKernels(int size, int parentSize) {
  static constexpr NodeKernels<D> kBodyUnderJoint[] = {kernelsFor<D, 6, 3>(), kernelsFor<D, 6, 4>(),
                                                       kernelsFor<D, 6, 5>(), kernelsFor<D, 6, 6>(),
                                                       kernelsFor<D, 6, 7>(), kernelsFor<D, 6, 8>()};
  static constexpr NodeKernels<D> kJointUnderBody[] = {kernelsFor<D, 3, 6>(), kernelsFor<D, 4, 6>(),
                                                       kernelsFor<D, 5, 6>(), kernelsFor<D, 6, 6>(),
                                                       kernelsFor<D, 7, 6>(), kernelsFor<D, 8, 6>()};
  if (size == 6 && parentSize >= 3 && parentSize <= 8) return kBodyUnderJoint[parentSize - 3];
  if (parentSize == 6 && size >= 3 && size <= 8) return kJointUnderBody[size - 3];
  return kernelsFor<D, 0, 0>();
}

template <typename D>
unsigned factor(const LaneNode* nodes, std::size_t count, double* matrices) {
  D ok = notEqualD(D::splat(0.0), D::splat(1.0));  // every lane
  for (std::size_t n = 0; n < count; ++n) {
    const LaneNode& node = nodes[n];
    const LaneNode* parent = node.parent >= 0 ? &nodes[node.parent] : nullptr;
    ok = andD(ok, nodeKernels<D>(node.size, parent ? parent->size : 0).eliminate(matrices, node, parent));
  }
  return maskBits(ok);
}

template <typename D>
void solve(const LaneNode* nodes, std::size_t count, const double* matrices, double* vectors) {
  for (std::size_t n = 0; n < count; ++n) {
    const LaneNode& node = nodes[n];
    const LaneNode* parent = node.parent >= 0 ? &nodes[node.parent] : nullptr;
    nodeKernels<D>(node.size, parent ? parent->size : 0).down(matrices, node, parent, vectors);
  }
  for (std::size_t n = count; n-- > 0;) {
    const LaneNode& node = nodes[n];
    const LaneNode* parent = node.parent >= 0 ? &nodes[node.parent] : nullptr;
    nodeKernels<D>(node.size, parent ? parent->size : 0).up(matrices, node, parent, vectors);
  }
}

}  // namespace lanes

}  // namespace collide::detail
