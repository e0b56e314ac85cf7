// The direct solve of joint trees (joint_tree.h).
#include "dynamics/joint_tree.h"

#include <atomic>
#include "base/assert.h"
#include "memory/heap_bytes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>

namespace collide::detail {

namespace {
std::atomic<bool> treeLanes{true};
std::atomic<std::uint32_t> lastGroupCount{0};
}  // namespace

void setTreeLanes(bool enabled) { treeLanes.store(enabled, std::memory_order_relaxed); }
std::uint32_t lastTreeLaneGroups() { return lastGroupCount.load(std::memory_order_relaxed); }

namespace {

// The rigid rows a joint type holds exactly (its equality rows); 0 for a type the tree does not take.
int equalityRowCount(const Joint& joint) {
  if (joint.softness.hertz > 0.0f) return 0;
  switch (joint.type) {
    case JointType::Ball:
    case JointType::Cone:
      return 3;
    case JointType::Hinge:
    case JointType::Slider:
      return 5;
    case JointType::Fixed:
      return joint.angularSoftness.hertz > 0.0f ? 0 : 6;
    case JointType::Distance:
      return 0;
  }
  return 0;
}

void equalityRows(const JointFrame& f, Joint& joint, EqualityRows& rows) {
  rows.count = 0;
  switch (joint.type) {
    case JointType::Ball:
      equalityRowsBall(f, joint, rows);
      break;
    case JointType::Hinge:
      equalityRowsHinge(f, joint, rows);
      break;
    case JointType::Slider:
      equalityRowsSlider(f, joint, rows);
      break;
    case JointType::Fixed:
      equalityRowsFixed(f, joint, rows);
      break;
    case JointType::Cone:
      equalityRowsCone(f, joint, rows);
      break;
    case JointType::Distance:
      break;
  }
}

// The limit rows a joint type can add to its tree (at most), and those it has now.
int limitRowCapacity(const Joint& joint) {
  switch (joint.type) {
    case JointType::Hinge:
    case JointType::Slider:
      return 2;
    case JointType::Cone:
      return 3;
    default:
      return 0;
  }
}

void limitRows(const JointFrame& f, Joint& joint, EqualityRows& rows, JointAngles& angles) {
  switch (joint.type) {
    case JointType::Hinge:
      limitRowsHinge(f, joint, rows, angles);
      break;
    case JointType::Slider:
      limitRowsSlider(f, joint, rows, angles);
      break;
    case JointType::Cone:
      limitRowsCone(f, joint, rows, angles);
      break;
    default:
      break;
  }
}

// The solver body a joint's end gives the tree: a dynamic rigid body the step moves. Static,
// kinematic and sleeping bodies are the ground the tree hangs from; a particle has no rotation for
// the rows' angular part, and its joints stay in the Gauss-Seidel passes.
std::int32_t treeBody(const JointSolverView& view, std::uint32_t body) {
  const std::int32_t j = view.solverOf[body];
  if (j == kNoSolverBody) return -1;
  const SolverBodyInfo& info = view.infos[static_cast<std::size_t>(j)];
  return info.dynamic && !info.particle && !info.faulted ? j : -1;
}

// Static, kinematic and sleeping bodies: the joint rows never write them.
bool isGround(const JointSolverView& view, std::uint32_t body) {
  const std::int32_t j = view.solverOf[body];
  return j == kNoSolverBody || !view.infos[static_cast<std::size_t>(j)].dynamic;
}

std::int32_t findRoot(Array<std::int32_t>& parent, std::int32_t i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

// Row i of a joint's Jacobian on one of its bodies: (linear, angular) on body B, minus on body A.
void jacobianRow(const JointRow& row, bool onB, double out[6]) {
  const double sign = onB ? 1.0 : -1.0;
  const Vec3& angular = onB ? row.angularB : row.angularA;
  for (int k = 0; k < 3; ++k) {
    out[k] = sign * row.linear[k];
    out[3 + k] = sign * angular[k];
  }
}

// The kernels of one node are templates on its size N and its parent's size C: 0 is a size known
// at run time only, and the common shapes (a body of 6 under a joint of 3 to 8 rows, a joint of 3
// to 8 rows under a body of 6) get loops of fixed length, which the compiler unrolls. The
// arithmetic is the same in every instance, in the same order.
template <int kN>
int fixedOr(int n) {
  return kN > 0 ? kN : n;
}

// In place LDL^T of the symmetric n x n matrix a (row-major, lower triangle read): L unit lower
// below the diagonal, D on it. No pivoting is needed: every node's matrix is quasi-definite, a
// body's masses (positive definite) and then its ground joint's rows, whose block is negative
// definite once the body is eliminated, and such a matrix factors stably in any order (Vanderbei,
// "Symmetric quasi-definite matrices", 1995). False if a pivot falls below a relative tolerance:
// rows that lost their rank.
template <int kN>
bool factorLdl(double* a, int size) {
  const int n = fixedOr<kN>(size);
  COLLIDE_ASSERT(n >= 0 && n <= kMaxNodeSize);  // the scratch row below holds kMaxNodeSize
  double scale = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k <= i; ++k) scale = std::max(scale, std::abs(a[i * n + k]));
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) return false;
  const double tolerance = 1e-12 * scale;
  double ld[kMaxNodeSize];  // row j of L times D
  for (int j = 0; j < n; ++j) {
    double* rowJ = a + j * n;
    double pivot = rowJ[j];
    for (int k = 0; k < j; ++k) {
      ld[k] = rowJ[k] * a[k * n + k];
      pivot -= rowJ[k] * ld[k];
    }
    if (!(std::abs(pivot) > tolerance)) return false;
    rowJ[j] = pivot;
    const double inversePivot = 1.0 / pivot;
    for (int i = j + 1; i < n; ++i) {
      double* rowI = a + i * n;
      double sum = rowI[j];
      for (int k = 0; k < j; ++k) sum -= rowI[k] * ld[k];
      rowI[j] = sum * inversePivot;
    }
  }
  return true;
}

// x = L^-1 x, the columns of the n x cols block x (row-major) in turn.
template <int kN, int kC>
void forwardSubstitute(const double* ldl, int size, double* x, int columns) {
  const int n = fixedOr<kN>(size);
  const int cols = fixedOr<kC>(columns);
  for (int i = 1; i < n; ++i) {
    for (int k = 0; k < i; ++k) {
      const double l = ldl[i * n + k];
      if (l == 0.0) continue;
      for (int c = 0; c < cols; ++c) x[i * cols + c] -= l * x[k * cols + c];
    }
  }
}

// One node's elimination (JointTree::factorTree): its D factored, its coupling y turned into
// L^-1 H, and the parent's D (cols x cols) less Y^T D^-1 Y. parentD null for a root.
template <int kN, int kC>
bool eliminateNode(double* ldl, int size, double* y, double* parentD, int parentSize) {
  if (!factorLdl<kN>(ldl, size)) return false;
  if (parentD == nullptr) return true;
  const int rows = fixedOr<kN>(size);
  const int cols = fixedOr<kC>(parentSize);
  forwardSubstitute<kN, kC>(ldl, rows, y, cols);
  for (int k = 0; k < rows; ++k) {
    const double* yk = y + k * cols;
    const double inversePivot = 1.0 / ldl[k * rows + k];
    for (int r = 0; r < cols; ++r) {
      const double scaled = yk[r] * inversePivot;
      if (scaled == 0.0) continue;
      for (int c = 0; c <= r; ++c) parentD[r * cols + c] -= scaled * yk[c];
    }
  }
  return true;
}

// The solve's way down (leaves first) at one node: u = D^-1 L^-1 z, z_parent -= Y^T u.
template <int kN, int kC>
void solveNodeDown(const double* ldl, int size, double* z, const double* y, double* zParent, int parentSize) {
  const int n = fixedOr<kN>(size);
  forwardSubstitute<kN, 1>(ldl, n, z, 1);
  for (int k = 0; k < n; ++k) z[k] /= ldl[k * n + k];
  if (zParent == nullptr) return;
  const int cols = fixedOr<kC>(parentSize);
  for (int k = 0; k < n; ++k) {
    const double* yk = y + k * cols;
    for (int c = 0; c < cols; ++c) zParent[c] -= yk[c] * z[k];
  }
}

// The way back (from the root) at one node: x = L^-T (u - D^-1 Y x_parent).
template <int kN, int kC>
void solveNodeUp(const double* ldl, int size, double* x, const double* y, const double* xParent,
                 int parentSize) {
  const int n = fixedOr<kN>(size);
  if (xParent != nullptr) {
    const int cols = fixedOr<kC>(parentSize);
    for (int r = 0; r < n; ++r) {
      double sum = 0.0;
      for (int k = 0; k < cols; ++k) sum += y[r * cols + k] * xParent[k];
      x[r] -= sum / ldl[r * n + r];
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    double sum = x[i];
    for (int k = i + 1; k < n; ++k) sum -= ldl[k * n + i] * x[k];
    x[i] = sum;
  }
}

// The instances for a node of this size under a parent of that size.
struct NodeKernels {
  bool (*eliminate)(double*, int, double*, double*, int);
  void (*down)(const double*, int, double*, const double*, double*, int);
  void (*up)(const double*, int, double*, const double*, const double*, int);
};
template <int kN, int kC>
constexpr NodeKernels kernelsFor() {
  return {&eliminateNode<kN, kC>, &solveNodeDown<kN, kC>, &solveNodeUp<kN, kC>};
}
constexpr NodeKernels kBodyUnderJoint[] = {kernelsFor<6, 3>(), kernelsFor<6, 4>(), kernelsFor<6, 5>(),
                                           kernelsFor<6, 6>(), kernelsFor<6, 7>(), kernelsFor<6, 8>()};
constexpr NodeKernels kJointUnderBody[] = {kernelsFor<3, 6>(), kernelsFor<4, 6>(), kernelsFor<5, 6>(),
                                           kernelsFor<6, 6>(), kernelsFor<7, 6>(), kernelsFor<8, 6>()};
NodeKernels nodeKernels(int size, int parentSize) {
  if (size == 6 && parentSize >= 3 && parentSize <= 8) return kBodyUnderJoint[parentSize - 3];
  if (parentSize == 6 && size >= 3 && size <= 8) return kJointUnderBody[size - 3];
  return kernelsFor<0, 0>();
}

}  // namespace

void JointTree::EntryRows::buildAtPose(const JointSolverView& view, Joint& joint) {
  frame = buildJointFrame(view, joint);
  ownFrame = frame;
  equalityRows(frame, joint, rows);
  equalityCount = rows.count;
}

void JointTree::prepare(const JointSolverView& view, Array<Joint>& joints) {
  entries_.clear();
  nodes_.clear();
  treeStart_.clear();
  units_.clear();
  lastGroupCount.store(0, std::memory_order_relaxed);
  joints_ = nullptr;
  entryOfJoint_.clear();
  if (joints.empty()) return;  // and the per-body scratch below is not grown
  const std::size_t bodyCount = view.bodies.size();
  parentOf_.resize(bodyCount);
  groundJoint_.assign(bodyCount, -1);
  grounded_.resize(bodyCount);
  adjacencyStart_.assign(bodyCount + 1, 0);

  // The forest, in joint order: a joint between two trees joins them, one within a tree closes a
  // loop and stays Gauss-Seidel. The ground counts as a body of each tree, once: a tree's first
  // joint to the ground joins its body's node, and a second (or a joint between two grounded trees)
  // closes a loop through the ground. Loops are where rows can be redundant (a bridge of parallel
  // hinges between two posts repeats its out-of-plane rows three times), which no pivot survives.
  //
  // A mesh of joints (a grid, a net, a truss), where loops close more than a third of the joints
  // (more loops than half its tree's joints), stays Gauss-Seidel whole: the loop joints' soft rows
  // pull its tree's rows open again after every exact solve, so that a projection fires each
  // substep, and the tree makes the step four times as long for no closer hold (the 10,000-sphere
  // joint grid: a mean gap of 8.7 mm with it, 8.2 without; docs/joints.md). A chain, a ragdoll, a
  // bridge between two posts or a closed linkage has a loop or two and keeps its tree.
  // The walk counts each component's tree and loop joints (at one of its bodies, added up by root
  // after); the meshes' entries then leave the forest, which leaves every other tree as it was.
  forestCounts_.assign(2 * bodyCount, 0);
  const auto countAt = [&](std::int32_t body, bool loop) {
    ++forestCounts_[2 * static_cast<std::size_t>(body) + (loop ? 1 : 0)];
  };
  std::iota(parentOf_.begin(), parentOf_.end(), 0);
  std::fill(grounded_.begin(), grounded_.end(), std::uint8_t{0});
  for (std::uint32_t i = 0; i < joints.size(); ++i) {
    Joint& joint = joints[i];
    joint.inTree = false;
    joint.treeLimits = 0;
    if (!joint.active || equalityRowCount(joint) == 0) continue;
    const std::int32_t a = treeBody(view, joint.bodyA);
    const std::int32_t b = treeBody(view, joint.bodyB);
    if (a == b) continue;  // both ground
    // A particle (or a body the guard stopped) is no ground: the joint's rows would move it, and
    // two trees solved side by side would both write it. Its joints stay Gauss-Seidel.
    if ((a < 0 && !isGround(view, joint.bodyA)) || (b < 0 && !isGround(view, joint.bodyB))) continue;
    if (a < 0 || b < 0) {
      const std::int32_t body = a < 0 ? b : a;
      const std::int32_t root = findRoot(parentOf_, body);
      if (grounded_[static_cast<std::size_t>(root)]) {
        countAt(body, true);
        continue;
      }
      grounded_[static_cast<std::size_t>(root)] = 1;
      groundJoint_[static_cast<std::size_t>(body)] = static_cast<std::int32_t>(entries_.size());
    } else {
      const std::int32_t rootA = findRoot(parentOf_, a);
      const std::int32_t rootB = findRoot(parentOf_, b);
      if (rootA == rootB ||
          (grounded_[static_cast<std::size_t>(rootA)] && grounded_[static_cast<std::size_t>(rootB)])) {
        countAt(a, true);
        if (rootA != rootB) countAt(b, true);  // a loop through the ground for each tree
        continue;
      }
      const std::int32_t merged = std::min(rootA, rootB);
      parentOf_[static_cast<std::size_t>(std::max(rootA, rootB))] = merged;
      grounded_[static_cast<std::size_t>(merged)] |=
          grounded_[static_cast<std::size_t>(std::max(rootA, rootB))];
      ++adjacencyStart_[static_cast<std::size_t>(a) + 1];
      ++adjacencyStart_[static_cast<std::size_t>(b) + 1];
    }
    countAt(a < 0 ? b : a, false);
    joint.inTree = true;
    Entry& entry = entries_.emplace_back();
    entry.joint = i;
    entry.bodyA = a;
    entry.bodyB = b;
  }
  // Each component's counts at its root; a mesh's bodies marked.
  for (std::size_t s = 0; s < bodyCount; ++s) {
    const auto root = static_cast<std::size_t>(findRoot(parentOf_, static_cast<std::int32_t>(s)));
    if (root == s) continue;
    forestCounts_[2 * root] += forestCounts_[2 * s];
    forestCounts_[2 * root + 1] += forestCounts_[2 * s + 1];
  }
  inMesh_.assign(bodyCount, 0);
  bool anyMesh = false;
  for (std::size_t s = 0; s < bodyCount; ++s) {
    const auto root = static_cast<std::size_t>(findRoot(parentOf_, static_cast<std::int32_t>(s)));
    inMesh_[s] = 2 * forestCounts_[2 * root + 1] > forestCounts_[2 * root] ? 1 : 0;
    anyMesh = anyMesh || inMesh_[s];
  }
  if (anyMesh) {
    // The meshes' entries leave; the others keep their order, and the ground joints their entries'
    // new places.
    // Reused: the roots are no longer needed, and a forest has at most one entry per body.
    Array<std::int32_t>& newIndex = parentOf_;
    std::size_t kept = 0;
    std::fill(adjacencyStart_.begin(), adjacencyStart_.end(), 0u);
    for (std::size_t e = 0; e < entries_.size(); ++e) {
      const Entry entry = entries_[e];
      const std::int32_t body = entry.bodyA < 0 ? entry.bodyB : entry.bodyA;
      if (inMesh_[static_cast<std::size_t>(body)]) {
        joints[entry.joint].inTree = false;
        continue;
      }
      newIndex[e] = static_cast<std::int32_t>(kept);
      if (entry.bodyA >= 0 && entry.bodyB >= 0) {
        ++adjacencyStart_[static_cast<std::size_t>(entry.bodyA) + 1];
        ++adjacencyStart_[static_cast<std::size_t>(entry.bodyB) + 1];
      }
      entries_[kept++] = entry;
    }
    entries_.resize(kept);
    for (std::size_t s = 0; s < bodyCount; ++s) {
      std::int32_t& ground = groundJoint_[s];
      if (ground >= 0) ground = inMesh_[s] ? -1 : newIndex[static_cast<std::size_t>(ground)];
    }
  }
  if (entries_.empty()) return;
  if (entryRows_.size() < entries_.size()) entryRows_.resize(entries_.size());

  // Each body's tree joints (entries), in entry order.
  for (std::size_t s = 0; s < bodyCount; ++s) adjacencyStart_[s + 1] += adjacencyStart_[s];
  adjacency_.assign(adjacencyStart_[bodyCount], 0);
  {
    Array<std::uint32_t> fill(adjacencyStart_.begin(), adjacencyStart_.end() - 1);
    for (std::uint32_t e = 0; e < entries_.size(); ++e) {
      const std::int32_t a = entries_[e].bodyA;
      const std::int32_t b = entries_[e].bodyB;
      if (a < 0 || b < 0) continue;
      adjacency_[fill[static_cast<std::size_t>(a)]++] = e;
      adjacency_[fill[static_cast<std::size_t>(b)]++] = e;
    }
  }

  // Each tree breadth first from its root; reversed, children come before parents. A grounded tree
  // is rooted at the body its ground joint holds, an other from its lowest solver body. Below a
  // joint node there must be no ground: a subtree held by it can be unable to move along one of the
  // joint's rows (a grid's link to the body beside a pin, along the line to the pin), and that
  // row's pivot is zero.
  bodyNode_.assign(bodyCount, -1);
  Array<Node> order;
  Array<std::int32_t> entryNode(entries_.size(), -1);
  for (std::size_t candidate = 0; candidate < 2 * bodyCount; ++candidate) {
    const std::size_t root = candidate % bodyCount;
    const bool grounded = groundJoint_[root] >= 0;
    if (candidate < bodyCount ? !grounded : grounded) continue;
    const bool hasJoints = adjacencyStart_[root + 1] > adjacencyStart_[root] || grounded;
    if (!hasJoints || bodyNode_[root] >= 0) continue;
    order.clear();
    Node rootNode;
    rootNode.body = static_cast<std::int32_t>(root);
    bodyNode_[root] = 0;
    order.push_back(rootNode);
    for (std::size_t next = 0; next < order.size(); ++next) {
      const Node node = order[next];
      if (node.body < 0) {
        // A joint node: its other body is its child.
        const std::int32_t a = entries_[static_cast<std::size_t>(node.joint)].bodyA;
        const std::int32_t b = entries_[static_cast<std::size_t>(node.joint)].bodyB;
        const std::int32_t child = bodyNode_[static_cast<std::size_t>(a)] < 0 ? a : b;
        Node body;
        body.body = child;
        body.parent = static_cast<std::int32_t>(next);
        bodyNode_[static_cast<std::size_t>(child)] = static_cast<std::int32_t>(order.size());
        order.push_back(body);
        continue;
      }
      const std::size_t s = static_cast<std::size_t>(node.body);
      for (std::uint32_t k = adjacencyStart_[s]; k < adjacencyStart_[s + 1]; ++k) {
        const std::uint32_t e = adjacency_[k];
        if (entryNode[e] >= 0) continue;  // the joint to the parent
        Node joint;
        joint.joint = static_cast<std::int32_t>(e);
        joint.parent = static_cast<std::int32_t>(next);
        entryNode[e] = static_cast<std::int32_t>(order.size());
        order.push_back(joint);
      }
    }
    // Reverse into nodes_: index i of order becomes first + (count - 1 - i).
    const std::uint32_t first = static_cast<std::uint32_t>(nodes_.size());
    const std::int32_t count = static_cast<std::int32_t>(order.size());
    treeStart_.push_back(first);
    for (std::int32_t i = count - 1; i >= 0; --i) {
      Node node = order[static_cast<std::size_t>(i)];
      if (node.parent >= 0) node.parent = static_cast<std::int32_t>(first) + (count - 1 - node.parent);
      if (node.body >= 0) {
        node.joint = groundJoint_[static_cast<std::size_t>(node.body)];
        bodyNode_[static_cast<std::size_t>(node.body)] = static_cast<std::int32_t>(nodes_.size());
      }
      const std::int32_t index = static_cast<std::int32_t>(nodes_.size());
      if (node.joint >= 0) entries_[static_cast<std::size_t>(node.joint)].node = index;
      nodes_.push_back(node);
    }
  }
  treeStart_.push_back(static_cast<std::uint32_t>(nodes_.size()));

  // Each tree's entries in entry order (a counting sort by tree).
  const std::size_t treeCount = treeStart_.size() - 1;
  Array<std::uint32_t> treeOfNode(nodes_.size());
  for (std::size_t t = 0; t < treeCount; ++t)
    std::fill(treeOfNode.begin() + treeStart_[t], treeOfNode.begin() + treeStart_[t + 1], std::uint32_t(t));
  treeEntryStart_.assign(treeCount + 1, 0);
  for (const Entry& entry : entries_) ++treeEntryStart_[treeOfNode[static_cast<std::size_t>(entry.node)] + 1];
  for (std::size_t t = 0; t < treeCount; ++t) treeEntryStart_[t + 1] += treeEntryStart_[t];
  treeEntries_.resize(entries_.size());
  {
    Array<std::uint32_t> fill(treeEntryStart_.begin(), treeEntryStart_.end() - 1);
    for (std::uint32_t e = 0; e < entries_.size(); ++e)
      treeEntries_[fill[treeOfNode[static_cast<std::size_t>(entries_[e].node)]]++] = e;
  }

  // Sizes and offsets.
  std::uint32_t matrices = 0;
  std::uint32_t vectors = 0;
  for (Node& node : nodes_) {
    int rows = 0;
    if (node.joint >= 0) {
      const Joint& joint = joints[entries_[static_cast<std::size_t>(node.joint)].joint];
      rows = equalityRowCount(joint) + limitRowCapacity(joint);
    }
    node.capacity = node.body >= 0 ? 6 + rows : rows;
  }
  for (Node& node : nodes_) {
    const int parentCapacity = node.parent >= 0 ? nodes_[static_cast<std::size_t>(node.parent)].capacity : 0;
    node.matrix = matrices;
    matrices += static_cast<std::uint32_t>(node.capacity * node.capacity);
    node.coupling = matrices;
    matrices += static_cast<std::uint32_t>(node.capacity * parentCapacity);
    node.vector = vectors;
    vectors += static_cast<std::uint32_t>(node.capacity);
  }
  matrices_.resize(matrices);
  addedInertia_.resize(bodyCount);
  projectionTurn_.resize(bodyCount);
  effectiveInverseInertia_.resize(bodyCount);
  for (const Node& node : nodes_) {
    if (node.body >= 0)
      effectiveInverseInertia_[static_cast<std::size_t>(node.body)] =
          view.infos[static_cast<std::size_t>(node.body)].inverseInertiaWorld;
  }
  rhs_.resize(vectors);
  solution_.resize(vectors);
  rowsAtPose_.assign(treeCount, 0);
  limitsAtPose_.assign(treeCount, 0);
  factored_.assign(treeCount, 0);
  std::size_t limitSlots = 0;
  for (Entry& entry : entries_) {
    if (limitRowCapacity(joints[entry.joint]) > 0) entry.limitSlot = static_cast<std::int32_t>(limitSlots++);
  }
  limitCandidates_.resize(limitSlots);
  limitAngles_.resize(limitSlots);
  treeSolved_.assign(treeCount, 1);  // every tree joint starts the step inTree
  joints_ = joints.data();
  entryOfJoint_.assign(joints.size(), -1);
  entryTree_.resize(entries_.size());
  for (std::size_t t = 0; t < treeCount; ++t) {
    for (std::uint32_t k = treeEntryStart_[t]; k < treeEntryStart_[t + 1]; ++k) {
      entryTree_[treeEntries_[k]] = static_cast<std::uint32_t>(t);
      entryOfJoint_[entries_[treeEntries_[k]].joint] = static_cast<std::int32_t>(treeEntries_[k]);
    }
  }
  groupTrees();
}

// Trees t and u have the same nodes in the same order: bodies and joints, parents and capacities
// (so their blocks lie at the same offsets from each tree's first).
bool JointTree::sameShape(std::size_t t, std::size_t u) const {
  const std::size_t firstT = treeStart_[t];
  const std::size_t firstU = treeStart_[u];
  const std::size_t count = treeStart_[t + 1] - firstT;
  if (treeStart_[u + 1] - firstU != count) return false;
  for (std::size_t i = 0; i < count; ++i) {
    const Node& a = nodes_[firstT + i];
    const Node& b = nodes_[firstU + i];
    const auto parentAt = [](const Node& node, std::size_t first) {
      return node.parent < 0 ? std::int64_t{-1} : std::int64_t{node.parent} - std::int64_t(first);
    };
    if ((a.body >= 0) != (b.body >= 0) || (a.joint >= 0) != (b.joint >= 0) || a.capacity != b.capacity ||
        parentAt(a, firstT) != parentAt(b, firstU))
      return false;
  }
  return true;
}

// The solve passes' units: runs of kTreeLanes trees of one shape become a group in lanes, the
// others stay alone. In tree order, so the grouping is the same at every worker count.
void JointTree::groupTrees() {
  units_.clear();
  laneNodes_.clear();
  std::size_t laneMatrices = 0;
  std::size_t laneVectors = 0;
  const std::size_t treeCount = treeStart_.size() - 1;
  std::size_t grouped = 0;  // trees in groups
  for (std::size_t t = 0; t < treeCount;) {
    TreeUnit unit;
    unit.firstTree = static_cast<std::uint32_t>(t);
    bool group = treeLanes.load(std::memory_order_relaxed) && t + kTreeLanes <= treeCount;
    for (std::size_t u = t + 1; group && u < t + kTreeLanes; ++u) group = sameShape(t, u);
    if (!group) {
      units_.push_back(unit);
      ++t;
      continue;
    }
    unit.treeCount = kTreeLanes;
    unit.nodeCount = static_cast<std::uint32_t>(treeStart_[t + 1] - treeStart_[t]);
    unit.laneNodes = static_cast<std::uint32_t>(laneNodes_.size());
    unit.laneMatrices = static_cast<std::uint32_t>(laneMatrices);
    unit.laneVectors = static_cast<std::uint32_t>(laneVectors);
    const std::size_t first = treeStart_[t];
    const std::size_t last = treeStart_[t + 1];
    const Node& firstNode = nodes_[first];
    for (std::size_t n = first; n < last; ++n) {
      const Node& node = nodes_[n];
      LaneNode lane;
      lane.parent = node.parent < 0 ? -1 : static_cast<std::int32_t>(std::size_t(node.parent) - first);
      lane.matrix = node.matrix - firstNode.matrix;
      lane.coupling = node.coupling - firstNode.matrix;
      lane.vector = node.vector - firstNode.vector;
      laneNodes_.push_back(lane);
    }
    const Node& lastNode = nodes_[last - 1];
    const std::size_t parentCapacity =
        lastNode.parent >= 0 ? std::size_t(nodes_[std::size_t(lastNode.parent)].capacity) : 0;
    laneMatrices += lastNode.coupling + std::size_t(lastNode.capacity) * parentCapacity - firstNode.matrix;
    laneVectors += lastNode.vector + std::size_t(lastNode.capacity) - firstNode.vector;
    units_.push_back(unit);
    t += kTreeLanes;
    grouped += kTreeLanes;
  }
  laneMatrices_.resize(laneMatrices * kTreeLanes);
  laneVectors_.resize(laneVectors * kTreeLanes);
  lastGroupCount.store(static_cast<std::uint32_t>(grouped / kTreeLanes), std::memory_order_relaxed);
}

// The rows of every tree joint at the current pose: its equality rows and the limits the tree
// takes this pass. At the warm start, the limits it took in the last pass (their impulses are the
// tree's to apply); in a solve pass, each limit reached (at or past it) or still pushing (its
// impulse above 0), the active set of the limits. A limit not taken is the Gauss-Seidel pass's.
// The biased pass comes at the warm start's pose (only velocities change in between), so it keeps
// the warm start's frames and equality rows and takes its limits afresh.
JointTree::BuiltRows JointTree::buildRows(const JointSolverView& view, Array<Joint>& joints, float h,
                                          RowPass pass, std::size_t t) {
  BuiltRows built;
  const bool rowsWereAtPose = rowsAtPose_[t] != 0;
  const bool framesNew = !(pass == RowPass::SolveAtWarmStartPose || rowsAtPose_[t]);
  const bool ahead = framesNew && jointBodiesOutgrowCache(view);
  const std::uint32_t end = treeEntryStart_[t + 1];
  for (std::uint32_t k = treeEntryStart_[t]; k < end; ++k) {
    // As the Gauss-Seidel waves do: the bodies of a joint a few entries on, asked for ahead.
    if (ahead && k + kJointBodiesAhead < end)
      prefetchJointBodies(view, joints[entries_[treeEntries_[k + kJointBodiesAhead]].joint]);
    Entry& entry = entries_[treeEntries_[k]];
    EntryRows& passRows = entryRows_[treeEntries_[k]];
    Joint& joint = joints[entry.joint];
    if (!framesNew) {
      passRows.rows.count = passRows.equalityCount;
    } else {
      passRows.buildAtPose(view, joint);
    }
    if (entry.limitSlot >= 0 && !limitsAtPose_[t]) buildLimitCandidates(entry, passRows.frame, joint);
    if (!joint.inTree || entry.limitSlot < 0) {
      joint.treeLimits = 0;
      continue;
    }
    const EqualityRows& candidates = limitCandidates_[static_cast<std::size_t>(entry.limitSlot)];
    std::uint8_t taken = 0;
    for (int i = 0; i < candidates.count; ++i) {
      const EqualityRow& row = candidates.rows[static_cast<std::size_t>(i)];
      const bool take = pass == RowPass::WarmStart ? (joint.treeLimits & row.limitBit) != 0
                                                   : row.error <= 0.0f || *row.accumulated > 0.0f;
      if (!take) continue;
      passRows.rows.rows[static_cast<std::size_t>(passRows.rows.count++)] = row;
      taken |= row.limitBit;
    }
    built.sameLimits = built.sameLimits && taken == joint.treeLimits;
    joint.treeLimits = taken;
    built.tookLimit = built.tookLimit || taken != 0;
  }
  rowsAtPose_[t] = 1;
  limitsAtPose_[t] = 1;
  // The stiffness comes with the rows of a new pose: the warm start at the relax pass's pose keeps
  // the relax pass's, and the biased pass after it can take that pass's factor.
  if (pass == RowPass::Solve || (pass == RowPass::WarmStart && !rowsWereAtPose)) {
    addGeometricStiffness(view, joints, h, t);
    factored_[t] = 0;
  }
  return built;
}

// Drops the limit rows of a tree whose impulse would pull (the solve's total below 0): those
// limits are not reached after all. False if none was.
bool JointTree::dropPullingLimits(Array<Joint>& joints, std::size_t first, std::size_t last,
                                  const Softness& soft) {
  bool dropped = false;
  for (std::size_t n = first; n < last; ++n) {
    const Node& node = nodes_[n];
    if (node.joint < 0) continue;
    Entry& entry = entries_[static_cast<std::size_t>(node.joint)];
    EntryRows& passRows = entryRows_[static_cast<std::size_t>(node.joint)];
    const double* lambda = solution_.data() + node.vector + (node.body >= 0 ? 6 : 0);
    // The limits follow the equality rows, which stay.
    int kept = passRows.equalityCount;
    for (int i = kept; i < passRows.rows.count; ++i) {
      EqualityRow& row = passRows.rows.rows[static_cast<std::size_t>(i)];
      const float total =
          *row.accumulated + soft.massScale * float(lambda[i]) - soft.impulseScale * *row.accumulated;
      if (total < 0.0f) {
        joints[entry.joint].treeLimits &= static_cast<std::uint8_t>(~row.limitBit);
        dropped = true;
        continue;
      }
      if (kept != i) passRows.rows.rows[static_cast<std::size_t>(kept)] = row;
      ++kept;
    }
    passRows.rows.count = kept;
  }
  return dropped;
}

// A light body pulled hard at an anchor off its centre (a chain link under a heavy load) swings
// back into line as a spring of stiffness |f| |r| about the axes across r: the load f turns with the
// body (the geometric stiffness of the joint force). Under a 1000 N load a 0.1 kg link does so at
// over 1000 rad/s, which the rows linearised at the substep's start overshoot whenever that rate
// times h passes 2: the link turns further each substep and the chain tears (a 100 kg ball under
// 20 such links). Tournier et al. ("Stable Constrained Dynamics", 2015) take the stiffness into
// the system implicitly; its share of the substep's inertia, h^2 f_r |r| (1 - r r^T / |r|^2), with
// f_r the joint's load's pull along r when the rows are built at a new pose, is what the tree's
// bodies get here (Tournier's |f| for any load gives a stiffness where there is none: a forearm
// pressed into the ground by its elbow). It is inertia only across the anchor's lever, at most a
// substep's worth: nothing for an unloaded joint, negligible for a limb carrying its weight, and it
// vanishes as h does. The tree's warm start and velocity passes, and the contacts
// (swapInverseInertia), turn the bodies through it; the joints' internal impulses still cancel, so
// momentum is kept. The projection uses the bodies' own inertia: through the stiffened one, its
// Newton steps after a plank chain's hard landing moved the planks off their rows instead of onto
// them.
void JointTree::addGeometricStiffness(const JointSolverView& view, Array<Joint>& joints, float h,
                                      std::size_t t) {
  const std::size_t first = treeStart_[t];
  const std::size_t last = treeStart_[t + 1];
  for (std::size_t n = first; n < last; ++n) {
    if (nodes_[n].body >= 0) addedInertia_[static_cast<std::size_t>(nodes_[n].body)] = Mat3(0.0f);
  }
  // The impulse's pull along the lever, out from the centre, and only that: a pulled anchor off the
  // centre swings back into line (the stiffness), a pushed one would swing away from it and a
  // sideways load does neither. A limb pressed between its joint and the ground is pushed: its
  // load, however large, adds nothing.
  const auto add = [&](std::int32_t body, const Vec3& r, const Vec3& impulse) {
    if (body < 0) return;
    const float lever = glm::length(r);
    if (!(lever > 0.0f)) return;
    const Vec3 n = r / lever;
    const float pull = glm::dot(impulse, n);
    if (!(pull > 0.0f)) return;
    addedInertia_[static_cast<std::size_t>(body)] +=
        (h * pull * lever) * (Mat3(1.0f) - glm::outerProduct(n, n));
  };
  for (std::uint32_t k = treeEntryStart_[t]; k < treeEntryStart_[t + 1]; ++k) {
    const Entry& entry = entries_[treeEntries_[k]];
    const EntryRows& passRows = entryRows_[treeEntries_[k]];
    const Joint& joint = joints[entry.joint];
    if (joint.type == JointType::Slider) continue;  // its linear rows hold no point
    // The point rows' impulse acts on b and, negated, on a.
    add(entry.bodyA, passRows.frame.rA, -joint.linearImpulse);
    add(entry.bodyB, passRows.frame.rB, joint.linearImpulse);
  }
  for (std::size_t n = first; n < last; ++n) {
    if (nodes_[n].body < 0) continue;
    const std::size_t body = static_cast<std::size_t>(nodes_[n].body);
    const Mat3& inverse = view.infos[body].inverseInertiaWorld;
    effectiveInverseInertia_[body] = addedInertia_[body] == Mat3(0.0f)
                                         ? inverse
                                         : glm::inverse(glm::inverse(inverse) + addedInertia_[body]);
  }
  for (std::uint32_t k = treeEntryStart_[t]; k < treeEntryStart_[t + 1]; ++k) {
    Entry& entry = entries_[treeEntries_[k]];
    EntryRows& passRows = entryRows_[treeEntries_[k]];
    if (entry.bodyA >= 0)
      passRows.frame.a.inverseInertia = effectiveInverseInertia_[static_cast<std::size_t>(entry.bodyA)];
    if (entry.bodyB >= 0)
      passRows.frame.b.inverseInertia = effectiveInverseInertia_[static_cast<std::size_t>(entry.bodyB)];
  }
}

void JointTree::buildStartRows(const JointSolverView& view, Array<Joint>& joints, float h,
                               TaskRunner& tasks) {
  if (entries_.empty()) return;
  forEachTree(tasks, [&](std::size_t t) { buildRows(view, joints, h, RowPass::WarmStart, t); });
}

void JointTree::swapInverseInertia(Array<SolverBodyInfo>& infos) {
  for (const Node& node : nodes_) {
    if (node.body >= 0)
      std::swap(infos[static_cast<std::size_t>(node.body)].inverseInertiaWorld,
                effectiveInverseInertia_[static_cast<std::size_t>(node.body)]);
  }
}

void JointTree::warmStart(const JointSolverView& view, Array<Joint>& joints, float h, TaskRunner& tasks) {
  if (entries_.empty()) return;
  forEachTree(tasks, [&](std::size_t t) {
    buildRows(view, joints, h, RowPass::WarmStart, t);
    for (std::uint32_t k = treeEntryStart_[t]; k < treeEntryStart_[t + 1]; ++k) {
      const Entry& entry = entries_[treeEntries_[k]];
      const EntryRows& passRows = entryRows_[treeEntries_[k]];
      if (!joints[entry.joint].inTree) continue;
      for (int i = 0; i < passRows.rows.count; ++i) {
        const EqualityRow& row = passRows.rows.rows[static_cast<std::size_t>(i)];
        applyRow(passRows.frame.a, passRows.frame.b, row.row, *row.accumulated);
      }
    }
  });
}

void JointTree::solve(const JointSolverView& view, Array<Joint>& joints, float h, float rigidHertz,
                      bool useBias, TaskRunner& tasks) {
  if (entries_.empty()) return;
  h_ = h;
  const Softness soft = rowSoftness(JointSoftness{}, rigidHertz, h, useBias);
  tasks.parallelFor(static_cast<std::uint32_t>(units_.size()), 1,
                    [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
                      for (std::uint32_t u = begin; u < end; ++u) {
                        TreeUnit& unit = units_[u];
                        if (unit.treeCount == 1) {
                          solveTreePass(view, joints, h, soft, useBias, unit.firstTree);
                        } else {
                          solveGroupPass(view, joints, h, soft, useBias, unit);
                        }
                      }
                    });
}

void JointTree::solveTreePass(const JointSolverView& view, Array<Joint>& joints, float h,
                              const Softness& soft, bool useBias, std::size_t t) {
  const BuiltRows built =
      buildRows(view, joints, h, useBias ? RowPass::SolveAtWarmStartPose : RowPass::Solve, t);
  // The biased pass at the relax pass's pose, with its stiffness and its limits, solves the same
  // system: the relax pass's factor is still in the blocks.
  const bool solved = solveRounds(view, joints, soft, t, built, factored_[t] != 0 && built.sameLimits, 0);
  finishTreePass(joints, soft, t, solved);
}

bool JointTree::solveRounds(const JointSolverView& view, Array<Joint>& joints, const Softness& soft,
                            std::size_t t, const BuiltRows& built, bool factored, int round) {
  const std::size_t first = treeStart_[t];
  const std::size_t last = treeStart_[t + 1];
  bool solved = false;
  for (; round < kLimitRounds; ++round) {
    if (factored) {
      fillRightHandSide(first, last, soft.biasRate, false);  // the blocks hold this system's factor
      solved = true;
    } else {
      solved = fillTree(view, first, last, soft.biasRate, false) && factorTree(first, last);
    }
    factored = false;
    if (!solved) break;
    solveTree(first, last);
    // Without a limit row there is nothing to drop: one round.
    if (!built.tookLimit || round + 1 == kLimitRounds || !dropPullingLimits(joints, first, last, soft)) break;
  }
  return solved;
}

void JointTree::finishTreePass(Array<Joint>& joints, const Softness& soft, std::size_t t, bool solved) {
  const std::size_t first = treeStart_[t];
  const std::size_t last = treeStart_[t + 1];
  factored_[t] = solved ? 1 : 0;
  // The joints learn only of a change: a tree solves pass after pass (joint_grid's 10,000 records
  // are not touched again).
  if (solved != (treeSolved_[t] != 0)) {
    treeSolved_[t] = solved ? 1 : 0;
    for (std::size_t n = first; n < last; ++n) {
      if (nodes_[n].joint < 0) continue;
      Joint& joint = joints[entries_[static_cast<std::size_t>(nodes_[n].joint)].joint];
      joint.inTree = solved;
      if (!solved) joint.treeLimits = 0;
    }
  }
  if (!solved) return;
  forEachRow(first, last, [&](EntryRows& passRows, EqualityRow& row, double lambda) {
    float impulse = soft.massScale * float(lambda) - soft.impulseScale * *row.accumulated;
    // A limit still pulling after the last round: held at zero, as the Gauss-Seidel row would.
    if (row.limitBit != 0) impulse = std::max(impulse, -*row.accumulated);
    *row.accumulated += impulse;
    applyRow(passRows.frame.a, passRows.frame.b, row.row, impulse);
  });
}

// The lanes' blocks (unless the lanes hold their factor) and right-hand sides for the trees of
// `lanes` (a bit per lane), at this pass's sizes: each tree's own, the group's the largest, what the
// padding needs zeroed first. Returns the lanes whose blocks could be filled.
unsigned JointTree::fillGroup(const JointSolverView& view, TreeUnit& unit, unsigned lanes, float biasRate,
                              bool factored) {
  LaneNode* laneNodes = laneNodes_.data() + unit.laneNodes;
  double* matrices = laneMatricesOf(unit);
  double* vectors = laneVectorsOf(unit);
  const auto firstOf = [&](std::uint32_t l) { return treeStart_[unit.firstTree + l]; };
  const auto lastOf = [&](std::uint32_t l) { return treeStart_[unit.firstTree + l + 1]; };
  for (std::uint32_t l = 0; l < kTreeLanes; ++l) {
    if (lanes >> l & 1u) setNodeSizes(firstOf(l), lastOf(l));
  }
  for (std::size_t i = 0; i < unit.nodeCount; ++i) {
    LaneNode& lane = laneNodes[i];
    int size = 0;
    for (std::uint32_t l = 0; l < kTreeLanes; ++l) {
      const int own = nodes_[firstOf(l) + i].size;
      lane.laneSize[l] = double(own);
      size = std::max(size, own);
    }
    lane.size = size;
  }
  if (!factored) {
    // D's lower triangle (the kernels read no other); the coupling only where a lane's tree has
    // fewer unknowns here or in the parent than the group (elsewhere every tree writes all of it).
    const auto padded = [](const LaneNode& lane) {
      for (std::uint32_t l = 0; l < kTreeLanes; ++l)
        if (lane.laneSize[l] != double(lane.size)) return true;
      return false;
    };
    for (std::size_t i = 0; i < unit.nodeCount; ++i) {
      const LaneNode& lane = laneNodes[i];
      double* d = matrices + std::size_t{lane.matrix} * kTreeLanes;
      for (int r = 0; r < lane.size; ++r)
        std::fill(d + std::size_t(r * lane.size) * kTreeLanes,
                  d + std::size_t(r * lane.size + r + 1) * kTreeLanes, 0.0);
      if (lane.parent < 0) continue;
      const LaneNode& parent = laneNodes[lane.parent];
      if (!padded(lane) && !padded(parent)) continue;
      double* coupling = matrices + std::size_t{lane.coupling} * kTreeLanes;
      std::fill(coupling, coupling + std::size_t(lane.size * parent.size) * kTreeLanes, 0.0);
    }
  }
  unsigned filled = lanes;
  for (std::uint32_t l = 0; l < kTreeLanes; ++l) {
    if (!(lanes >> l & 1u)) continue;
    const BlockLayout layout{matrices + l, vectors + l, laneNodes};
    if (!factored && !fillBlocks(view, firstOf(l), lastOf(l), false, layout)) filled &= ~(1u << l);
    fillRightHandSide(firstOf(l), lastOf(l), biasRate, false, layout);
  }
  return filled;
}

// Lane l's solution into its tree's own (solution_), where forEachRow reads it.
void JointTree::copySolution(const TreeUnit& unit, std::uint32_t l) {
  const LaneNode* laneNodes = laneNodes_.data() + unit.laneNodes;
  const double* vectors = laneVectorsOf(unit);
  const std::size_t first = treeStart_[unit.firstTree + l];
  for (std::size_t i = 0; i < unit.nodeCount; ++i) {
    const Node& node = nodes_[first + i];
    for (int r = 0; r < node.size; ++r)
      solution_[node.vector + std::size_t(r)] =
          vectors[(laneNodes[i].vector + std::size_t(r)) * kTreeLanes + l];
  }
}

// The group's trees are laid out in its lane records at the largest of their sizes, the rest
// padding; each tree's blocks are filled as a tree alone fills its own (fillBlocks), every
// kTreeLanes-th double. The rounds are the ones of solveRounds, for the lanes still in them: where
// every tree takes the limits of the last pass, whose factor the lanes hold, only the right-hand
// side is new; a tree whose limits came out pulling is filled, factored and solved again without
// them, beside the others of its group that are (the other lanes' results are not read).
void JointTree::solveGroupPass(const JointSolverView& view, Array<Joint>& joints, float h,
                               const Softness& soft, bool useBias, TreeUnit& unit) {
  const RowPass pass = useBias ? RowPass::SolveAtWarmStartPose : RowPass::Solve;
  BuiltRows built[kTreeLanes];
  bool reuse = unit.laneFactored;
  for (std::uint32_t l = 0; l < kTreeLanes; ++l) {
    const std::size_t t = unit.firstTree + l;
    built[l] = buildRows(view, joints, h, pass, t);
    reuse = reuse && factored_[t] != 0 && built[l].sameLimits;
  }
  LaneNode* laneNodes = laneNodes_.data() + unit.laneNodes;
  double* matrices = laneMatricesOf(unit);
  double* vectors = laneVectorsOf(unit);
  unsigned active = (1u << kTreeLanes) - 1;  // the lanes still in the rounds
  unsigned solved = 0;
  for (int round = 0; active != 0 && round < kLimitRounds; ++round) {
    const bool factored = round == 0 && reuse;
    const unsigned filled = fillGroup(view, unit, active, soft.biasRate, factored);
    if (!factored) {
      unit.laneOk = treeLaneKernels().factor(laneNodes, unit.nodeCount, matrices);
      // A later round's lanes hold only the factors of the trees still in it.
      unit.laneFactored = round == 0;
    }
    treeLaneKernels().solve(laneNodes, unit.nodeCount, matrices, vectors);
    unsigned next = 0;
    for (std::uint32_t l = 0; l < kTreeLanes; ++l) {
      if (!(active >> l & 1u)) continue;
      if (!((filled & unit.laneOk) >> l & 1u)) {
        solved &= ~(1u << l);
        continue;
      }
      solved |= 1u << l;
      copySolution(unit, l);
      // Without a limit row there is nothing to drop: one round.
      const std::size_t t = unit.firstTree + l;
      if (built[l].tookLimit && round + 1 < kLimitRounds &&
          dropPullingLimits(joints, treeStart_[t], treeStart_[t + 1], soft))
        next |= 1u << l;
    }
    active = next;
  }
  for (std::uint32_t l = 0; l < kTreeLanes; ++l)
    finishTreePass(joints, soft, unit.firstTree + l, (solved >> l & 1u) != 0);
}

void JointTree::project(const JointSolverView& view, Array<Joint>& joints, TaskRunner& tasks) {
  if (entries_.empty()) return;
  forEachTree(tasks, [&](std::size_t t) { projectTree(view, joints, t); });
}

void JointTree::projectTree(const JointSolverView& view, Array<Joint>& joints, std::size_t t) {
  const std::size_t first = treeStart_[t];
  const std::size_t last = treeStart_[t + 1];
  for (int iteration = 0; iteration < kTreeProjectionIterations; ++iteration) {
    if (!rowsOff(view, joints, t)) break;
    factored_[t] = 0;  // the blocks take the projection's system
    if (!fillTree(view, first, last, 1.0f, true) || !factorTree(first, last)) break;
    solveTree(first, last);
    moveOntoRows(view, t);
  }
}

// Tree t's rows at the current pose, and whether one is off by more than the slop. If none is, its
// limits too: this is the pose the relax pass comes at, and the Gauss-Seidel pass before it takes
// their angles (anglesAtPose), measured once.
bool JointTree::rowsOff(const JointSolverView& view, Array<Joint>& joints, std::size_t t) {
  const std::size_t first = treeStart_[t];
  const std::size_t last = treeStart_[t + 1];
  buildTreeRows(view, joints, first, last);
  rowsAtPose_[t] = 1;
  bool off = false;
  forEachRow(first, last, [&](EntryRows&, EqualityRow& row, double) {
    off = off || !(std::abs(row.error) <= kBallJointGapSlop);
  });
  if (off) return true;
  if (!limitsAtPose_[t]) {
    for (std::uint32_t k = treeEntryStart_[t]; k < treeEntryStart_[t + 1]; ++k) {
      const Entry& entry = entries_[treeEntries_[k]];
      if (entry.limitSlot >= 0)
        buildLimitCandidates(entry, entryRows_[treeEntries_[k]].frame, joints[entry.joint]);
    }
    limitsAtPose_[t] = 1;
  }
  return false;
}

// The projection's Newton step on tree t's bodies, by the last solve's lambda (K lambda = -C): each
// body moved by M^-1 G^T lambda, the turns of all its rows summed before it turns once. Turned row
// by row, a light body between heavy ones (a hub welded to four blades) took each row's turn, radians
// where its rows' impulses are large, whole before the next one's turned it back, and a quaternion
// stepped by radians is far from the linear step: the step left the rows further off than it found
// them.
void JointTree::moveOntoRows(const JointSolverView& view, std::size_t t) {
  const std::size_t first = treeStart_[t];
  const std::size_t last = treeStart_[t + 1];
  for (std::size_t n = first; n < last; ++n) {
    if (nodes_[n].body >= 0) projectionTurn_[static_cast<std::size_t>(nodes_[n].body)] = Vec3(0.0f);
  }
  for (std::size_t n = first; n < last; ++n) {
    const Node& node = nodes_[n];
    if (node.joint < 0) continue;
    const Entry& entry = entries_[static_cast<std::size_t>(node.joint)];
    const EntryRows& passRows = entryRows_[static_cast<std::size_t>(node.joint)];
    const JointBody& a = passRows.frame.a;
    const JointBody& b = passRows.frame.b;
    const double* lambda = solution_.data() + node.vector + (node.body >= 0 ? 6 : 0);
    for (int i = 0; i < passRows.rows.count; ++i) {
      const JointRow& row = passRows.rows.rows[static_cast<std::size_t>(i)].row;
      const auto l = float(lambda[i]);
      if (entry.bodyA >= 0) {
        a.solver->deltaPosition -= (a.inverseMass * l) * row.linear;
        projectionTurn_[static_cast<std::size_t>(entry.bodyA)] -= a.inverseInertia * (l * row.angularA);
      }
      if (entry.bodyB >= 0) {
        b.solver->deltaPosition += (b.inverseMass * l) * row.linear;
        projectionTurn_[static_cast<std::size_t>(entry.bodyB)] += b.inverseInertia * (l * row.angularB);
      }
    }
  }
  for (std::size_t n = first; n < last; ++n) {
    if (nodes_[n].body < 0) continue;
    const auto body = static_cast<std::size_t>(nodes_[n].body);
    turnSolverBody(view.bodies[body], projectionTurn_[body]);
  }
  rowsAtPose_[t] = 0;
  limitsAtPose_[t] = 0;
}

// The limit rows an entry's joint could add at the frame's pose, and its angles there.
void JointTree::buildLimitCandidates(const Entry& entry, const JointFrame& frame, Joint& joint) {
  const auto slot = static_cast<std::size_t>(entry.limitSlot);
  limitCandidates_[slot].count = 0;
  limitRows(frame, joint, limitCandidates_[slot], limitAngles_[slot]);
}

// The rows of one tree at the current pose (the projection's: bodies with their own inertia).
void JointTree::buildTreeRows(const JointSolverView& view, Array<Joint>& joints, std::size_t first,
                              std::size_t last) {
  const bool ahead = jointBodiesOutgrowCache(view);
  for (std::size_t n = first; n < last; ++n) {
    // A joint's node is every other one or so: this asks for one a few joints on.
    const std::size_t next = n + 2 * kJointBodiesAhead;
    if (ahead && next < last && nodes_[next].joint >= 0)
      prefetchJointBodies(view, joints[entries_[static_cast<std::size_t>(nodes_[next].joint)].joint]);
    if (nodes_[n].joint < 0) continue;
    Entry& entry = entries_[static_cast<std::size_t>(nodes_[n].joint)];
    EntryRows& passRows = entryRows_[static_cast<std::size_t>(nodes_[n].joint)];
    Joint& joint = joints[entry.joint];
    passRows.buildAtPose(view, joint);
  }
}

// D of every node of a tree (a body's masses and its ground joint's rows; zero for a joint), H(node,
// parent) (minus the joint's Jacobian on the body, transposed where the body is the child) and the
// right-hand side G v + b at the bodies' current velocities. False if a body cannot take part
// (stopped by the fault guard, or an inertia without an inverse).
bool JointTree::fillTree(const JointSolverView& view, std::size_t first, std::size_t last, float biasRate,
                         bool positions) {
  setNodeSizes(first, last);
  return fillBlocks(view, first, last, positions, BlockLayout{matrices_.data(), rhs_.data()}) &&
         (fillRightHandSide(first, last, biasRate, positions), true);
}

void JointTree::setNodeSizes(std::size_t first, std::size_t last) {
  for (std::size_t n = first; n < last; ++n) {
    Node& node = nodes_[n];
    const int rows = node.joint >= 0 ? entryRows_[static_cast<std::size_t>(node.joint)].rows.count : 0;
    node.size = (node.body >= 0 ? 6 : 0) + rows;
  }
}

JointTree::NodeBlocks JointTree::blocksOf(const BlockLayout& layout, std::size_t first, std::size_t n) const {
  const Node& node = nodes_[n];
  if (layout.lanes == nullptr) {
    const Node* parent = parentOf(node);
    return {layout.matrices + node.matrix, layout.matrices + node.coupling,
            layout.vectors + node.vector,  node.size,
            parent ? parent->size : 0,     1};
  }
  const LaneNode& lane = layout.lanes[n - first];
  const std::size_t stride = kTreeLanes;
  return {layout.matrices + lane.matrix * stride,
          layout.matrices + lane.coupling * stride,
          layout.vectors + lane.vector * stride,
          lane.size,
          lane.parent >= 0 ? layout.lanes[static_cast<std::size_t>(lane.parent)].size : 0,
          stride};
}

// A tree alone zeroes its D here; laid out in a group's lanes, the blocks are at the group's sizes
// and fillGroup has zeroed what this leaves (D's lower triangle, padded couplings) for all lanes.
bool JointTree::fillBlocks(const JointSolverView& view, std::size_t first, std::size_t last, bool positions,
                           const BlockLayout& layout) {
  double g[6];
  for (std::size_t n = first; n < last; ++n) {
    const Node& node = nodes_[n];
    const NodeBlocks blocks = blocksOf(layout, first, n);
    const int size = blocks.size;
    const std::size_t stride = blocks.stride;
    const auto d = [&](int r, int c) -> double& { return blocks.d[std::size_t(r * size + c) * stride]; };
    if (stride == 1) std::fill(blocks.d, blocks.d + size * size, 0.0);
    int rowsAt = 0;  // where the node's joint rows start among its unknowns
    if (node.body >= 0) {
      const SolverBodyInfo& info = view.infos[static_cast<std::size_t>(node.body)];
      if (info.faulted || !(info.inverseMass > 0.0f)) return false;
      const glm::dmat3 inverseInertia(positions
                                          ? info.inverseInertiaWorld
                                          : effectiveInverseInertia_[static_cast<std::size_t>(node.body)]);
      if (!(std::abs(glm::determinant(inverseInertia)) > 0.0)) return false;
      const glm::dmat3 inertia = glm::inverse(inverseInertia);
      const double mass = 1.0 / double(info.inverseMass);
      for (int k = 0; k < 3; ++k) {
        d(k, k) = mass;
        for (int c = 0; c < 3; ++c) d(3 + k, 3 + c) = inertia[c][k];
      }
      rowsAt = 6;
    }
    if (node.joint >= 0 && node.body >= 0) {
      const Entry& entry = entries_[static_cast<std::size_t>(node.joint)];
      const EntryRows& passRows = entryRows_[static_cast<std::size_t>(node.joint)];
      for (int i = 0; i < passRows.rows.count; ++i) {
        const EqualityRow& row = passRows.rows.rows[static_cast<std::size_t>(i)];
        // A ground joint's rows within its body's node: [[M, -G^T], [-G, 0]].
        jacobianRow(row.row, entry.bodyB == node.body, g);
        for (int k = 0; k < 6; ++k) {
          d(rowsAt + i, k) = -g[k];
          d(k, rowsAt + i) = -g[k];
        }
      }
    }
    if (node.parent < 0) continue;
    const Node& parent = nodes_[static_cast<std::size_t>(node.parent)];
    const int parentSize = blocks.parentSize;
    const auto coupling = [&](int r, int c) -> double& {
      return blocks.coupling[std::size_t(r * parentSize + c) * stride];
    };
    if (node.body >= 0) {
      // A body under the joint that holds it: H(body, joint) = -G^T, rows 0..5.
      const Entry& entry = entries_[static_cast<std::size_t>(parent.joint)];
      const EntryRows& passRows = entryRows_[static_cast<std::size_t>(parent.joint)];
      for (int i = 0; i < passRows.rows.count; ++i) {
        jacobianRow(passRows.rows.rows[static_cast<std::size_t>(i)].row, entry.bodyB == node.body, g);
        for (int k = 0; k < 6; ++k) coupling(k, i) = -g[k];
      }
    } else {
      // A joint under one of its bodies: H(joint, body) = -G, columns 0..5 (the rest of a row is
      // the ground joint's of a body that has one).
      const Entry& entry = entries_[static_cast<std::size_t>(node.joint)];
      const EntryRows& passRows = entryRows_[static_cast<std::size_t>(node.joint)];
      for (int i = 0; i < passRows.rows.count; ++i) {
        jacobianRow(passRows.rows.rows[static_cast<std::size_t>(i)].row, entry.bodyB == parent.body, g);
        for (int k = 0; k < 6; ++k) coupling(i, k) = -g[k];
        for (int k = 6; k < parent.size; ++k) coupling(i, k) = 0.0;
      }
    }
  }
  return true;
}

void JointTree::fillRightHandSide(std::size_t first, std::size_t last, float biasRate, bool positions) {
  fillRightHandSide(first, last, biasRate, positions, BlockLayout{matrices_.data(), rhs_.data()});
}

// The right-hand side alone: G v + biasRate C per row (C alone for the projection), 0 for a body's
// own unknowns (and a group's padding).
void JointTree::fillRightHandSide(std::size_t first, std::size_t last, float biasRate, bool positions,
                                  const BlockLayout& layout) {
  for (std::size_t n = first; n < last; ++n) {
    const Node& node = nodes_[n];
    const NodeBlocks blocks = blocksOf(layout, first, n);
    const auto rhs = [&](int r) -> double& { return blocks.vector[std::size_t(r) * blocks.stride]; };
    for (int r = 0; r < blocks.size; ++r) rhs(r) = 0.0;
    const int rowsAt = node.body >= 0 ? 6 : 0;
    if (node.joint < 0) continue;
    const EntryRows& passRows = entryRows_[static_cast<std::size_t>(node.joint)];
    for (int i = 0; i < passRows.rows.count; ++i) {
      const EqualityRow& row = passRows.rows.rows[static_cast<std::size_t>(i)];
      const double speed = positions ? 0.0 : double(rowSpeed(passRows.frame.a, passRows.frame.b, row.row));
      // A limit not reached yet is speculative: only the approach that would cross it this
      // substep (limitImpulse's rule).
      const double bias = row.limitBit != 0 && row.error > 0.0f ? double(row.error) / double(h_)
                                                                : double(biasRate) * double(row.error);
      rhs(rowsAt + i) = speed + bias;
    }
  }
}

// Leaves first: each node's D = L D L^T, its coupling turned into Y = L^-1 H(node, parent), and
// the parent's D less H^T D^-1 H = Y^T D^-1 Y (the Schur complement; on a tree it touches the
// parent only). Only lower triangles are read.
bool JointTree::factorTree(std::size_t first, std::size_t last) {
  for (std::size_t n = first; n < last; ++n) {
    const Node& node = nodes_[n];
    const Node* parent = parentOf(node);
    const int parentSize = parent ? parent->size : 0;
    double* parentD = parent ? matrices_.data() + parent->matrix : nullptr;
    if (!nodeKernels(node.size, parentSize)
             .eliminate(matrices_.data() + node.matrix, node.size, matrices_.data() + node.coupling, parentD,
                        parentSize))
      return false;
  }
  return true;
}

// Forward (leaves first) u = D^-1 L^-1 z, z_parent -= Y^T u; then back from the root
// x = L^-T (u - D^-1 Y x_parent): the rows' impulses, lambda = -K^-1 rhs.
void JointTree::solveTree(std::size_t first, std::size_t last) {
  std::copy(rhs_.begin() + nodes_[first].vector,
            rhs_.begin() + nodes_[last - 1].vector + nodes_[last - 1].size,
            solution_.begin() + nodes_[first].vector);
  // Node n's kernel of one sweep (kernelOf picks it), on its blocks and its parent's unknowns.
  const auto sweep = [&](std::size_t n, auto kernelOf) {
    const Node& node = nodes_[n];
    const Node* parent = parentOf(node);
    const int parentSize = parent ? parent->size : 0;
    kernelOf(nodeKernels(node.size, parentSize))(
        matrices_.data() + node.matrix, node.size, solution_.data() + node.vector,
        matrices_.data() + node.coupling, parent ? solution_.data() + parent->vector : nullptr, parentSize);
  };
  for (std::size_t n = first; n < last; ++n) sweep(n, [](const NodeKernels& k) { return k.down; });
  for (std::size_t n = last; n-- > first;) sweep(n, [](const NodeKernels& k) { return k.up; });
}

std::size_t JointTree::memoryBytes() const {
  return heapBytes(entries_) + heapBytes(entryRows_) + heapBytes(nodes_) + heapBytes(treeStart_) +
         heapBytes(treeEntries_) + heapBytes(treeEntryStart_) + heapBytes(rowsAtPose_) +
         heapBytes(treeSolved_) + heapBytes(factored_) + heapBytes(limitCandidates_) +
         heapBytes(limitAngles_) + heapBytes(limitsAtPose_) + heapBytes(matrices_) + heapBytes(rhs_) +
         heapBytes(solution_) + heapBytes(units_) + heapBytes(laneNodes_) + heapBytes(laneMatrices_) +
         heapBytes(laneVectors_) + heapBytes(parentOf_) + heapBytes(groundJoint_) + heapBytes(grounded_) +
         heapBytes(forestCounts_) + heapBytes(inMesh_) + heapBytes(adjacencyStart_) + heapBytes(adjacency_) +
         heapBytes(bodyNode_) + heapBytes(addedInertia_) + heapBytes(projectionTurn_) +
         heapBytes(effectiveInverseInertia_) + heapBytes(entryOfJoint_) + heapBytes(entryTree_);
}

}  // namespace collide::detail
