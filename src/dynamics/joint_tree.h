// The direct solve of joint trees (Baraff, "Linear-Time Dynamics using Lagrange Multipliers",
// SIGGRAPH 1996). Gauss-Seidel passes information one joint per pass, so a heavy body at the end of
// a light chain, a bridge under a load or a ragdoll's limbs stretch their joints until the passes
// catch up. Solved as one system, the rigid rows of a tree of joints are met exactly in each pass,
// whatever the masses.
//
// The system of a pass, for the velocity change dv of the bodies and the impulses lambda of the
// rows (M the bodies' masses, G the rows' Jacobian, v the velocities, b the position bias):
//   [ M  -G^T ] [ dv     ]   [ 0      ]
//   [ -G   0  ] [ lambda ] = [ Gv + b ]
// Its graph has a node per body and per joint, an edge where a joint holds a body. On a tree,
// eliminating the nodes leaves first (children before parents) makes no fill: a block LDL^T in
// time linear in the nodes. A joint to a static or kinematic body has one body node; its rows join
// that body's node (a joint node with no child would have a zero pivot). A joint that closes a
// loop (through the ground too: a tree hangs from it by one joint at most), a soft joint and a
// distance joint stay in the Gauss-Seidel passes (joint_solver.h), as do every joint's springs,
// motors and limits.
//
// The solution lambda is the rows' whole impulse for the pass; the soft step applies
// massScale * lambda - impulseScale * accumulated, the rule of every soft row (contact_solver.h)
// with the tree's coupled effective mass in place of the row's own.
#pragma once

#include "base/task_runner.h"
#include "dynamics/joint_solver.h"
#include "dynamics/joint_tree_lanes.h"
#include "dynamics/joints/joint_rows.h"

#include <cstdint>
#include <vector>

namespace collide::detail {

// Newton steps of the projection at most, each from the rows at the pose the last one left.
inline constexpr int kTreeProjectionIterations = 4;
// Solves of a pass at most: after each, the limits whose impulse would pull leave the tree.
inline constexpr int kLimitRounds = 3;
// A node's unknowns at most: a body's six and a ground joint's rows with its limits.
inline constexpr int kMaxNodeSize = 6 + kMaxJointTreeRows;

class JointTree {
 public:
  // Once per step, after prepareJoints: the forest of the active rigid joints and its order.
  void prepare(const JointSolverView& view, Array<Joint>& joints);
  // Once per step, after prepare and before the contacts are prepared: each tree's rows and their
  // geometric stiffness at the step's start pose (the first substep's warm start takes them as they
  // are), so that the contacts can meet a tree's bodies with the inertia the tree solves them with.
  void buildStartRows(const JointSolverView& view, Array<Joint>& joints, float h, TaskRunner& tasks);
  // Swaps each tree body's inverse inertia in `infos` with the one its tree solves it with (its own
  // plus the stiffness of its joints' pull): called before and after the contacts are prepared,
  // their rows take the tree's, one inertia for one body as in Tournier's implicit step. Without
  // it a limb whose tree stiffens it meets its contacts as the lighter body it is not, the two
  // solves disagree on how it turns, and at few substeps they fight until the limb is flung.
  void swapInverseInertia(Array<SolverBodyInfo>& infos);
  // Trees share no body that moves, so each pass takes them in parallel on the step's workers
  // (tasks); the answer does not depend on which worker solved which tree.
  //
  // Per substep, after JointWaves::warmStart (which leaves a tree joint's rigid rows out): the rows'
  // accumulated impulses applied, through the inertia the tree's bodies solve with.
  void warmStart(const JointSolverView& view, Array<Joint>& joints, float h, TaskRunner& tasks);
  // One pass (useBias as in JointWaves::solve): each tree's rows at the bodies' current pose, factored and
  // solved, the impulses applied. A tree whose factor fails (rows that lost their rank) hands its
  // joints to the Gauss-Seidel pass that follows (Joint::inTree false for that pass). The biased
  // pass must follow warmStart with no position update between: it reuses the warm start's rows,
  // and, where the limits it takes are the last pass's, that pass's factor.
  void solve(const JointSolverView& view, Array<Joint>& joints, float h, float rigidHertz, bool useBias,
             TaskRunner& tasks);

  // After the position update: a tree whose rows are off by more than kBallJointGapSlop (m or rad)
  // is moved back onto them by Newton steps on positions through the same system, K lambda = -C
  // (post-stabilisation, Cline and Pai 2003), with the bodies' own inertia. Velocities are not
  // touched. A whipping chain opens its joints by the curvature of its links' paths, which no
  // velocity row sees.
  void project(const JointSolverView& view, Array<Joint>& joints, TaskRunner& tasks);

  // The bodies moved (the position update, a projection): the trees' rows are rebuilt at the next
  // pass. Until then a pass takes the rows the last one built at the same pose (the next
  // substep's warm start those of the relax pass, the relax pass those of a projection that found
  // nothing off), with the same values.
  void posesMoved() {
    std::fill(rowsAtPose_.begin(), rowsAtPose_.end(), std::uint8_t{0});
    std::fill(limitsAtPose_.begin(), limitsAtPose_.end(), std::uint8_t{0});
    std::fill(factored_.begin(), factored_.end(), std::uint8_t{0});
  }

  // The frame the tree built for this joint at the bodies' current pose (its tree's rows are at
  // the pose: built since the bodies last moved), with the bodies' own masses, or null. Read by the
  // Gauss-Seidel passes, which need the frames of tree joints for their limits, motors and friction
  // at the same poses.
  const JointFrame* frameAtPose(const Joint& joint) const {
    const std::int32_t entry = entryAt(joint);
    if (entry < 0 || rowsAtPose_[entryTree_[static_cast<std::size_t>(entry)]] == 0) return nullptr;
    return &entryRows_[static_cast<std::size_t>(entry)].ownFrame;
  }

  // The angles the tree measured for this joint's limits at the bodies' current pose (its
  // tree's limits are at the pose), or null. Read by the Gauss-Seidel passes, whose limits, springs
  // and motors take the same angles at the same poses.
  const JointAngles* anglesAtPose(const Joint& joint) const {
    const std::int32_t entry = entryAt(joint);
    if (entry < 0) return nullptr;
    const Entry& e = entries_[static_cast<std::size_t>(entry)];
    if (e.limitSlot < 0 || limitsAtPose_[entryTree_[static_cast<std::size_t>(entry)]] == 0) return nullptr;
    return &limitAngles_[static_cast<std::size_t>(e.limitSlot)];
  }

  // Joints solved in trees this step (for tests and statistics).
  std::size_t jointCount() const { return entries_.size(); }

  std::size_t memoryBytes() const;  // World::memoryUse

 private:
  struct Node {
    std::int32_t body = -1;    // solver body of a body node, -1 for a joint node
    std::int32_t joint = -1;   // entry in entries_ of a joint node, or of a body node's ground joint
    std::int32_t parent = -1;  // node index, -1 for a root
    int size = 0;      // this pass's unknowns: 6 (+ the ground joint's rows) for a body, the rows for a joint
    int capacity = 0;  // the most it can have (every limit taken); its blocks are laid out for it
    std::uint32_t matrix = 0;    // offset of D, then D^-1 (size x size) in matrices_
    std::uint32_t coupling = 0;  // offset of H(node, parent), then D^-1 H (size x parent's size)
    std::uint32_t vector = 0;    // offset of the node's unknowns in rhs_ and solution_
  };
  // A joint of the forest, made afresh each step.
  struct Entry {
    std::uint32_t joint = 0;  // index in the world's joints
    std::int32_t node = -1;   // its joint node, or the body node whose ground joint it is
    std::int32_t bodyA = -1;  // its bodies' solver bodies in the tree, -1 for the ground
    std::int32_t bodyB = -1;
    std::int32_t limitSlot = -1;  // its limit rows' place in limitCandidates_, -1 without limits
  };
  // An entry's rows and frame (entryRows_, by entry), about 700 bytes, which every pass writes
  // before it reads them: kept from step to step rather than zeroed with each new entry (the joint
  // grid's 10,000 forest joints made that most of prepare's time).
  struct EntryRows {
    EqualityRows rows;      // this pass's rows: the equality rows, then the limits taken
    int equalityCount = 0;  // the equality rows among them
    JointFrame frame;       // this pass's bodies and frame (with the inertia the tree solves with)
    JointFrame ownFrame;    // the same with the bodies' own masses, for the Gauss-Seidel passes
    // The frames and equality rows at the bodies' current pose (no limit taken yet).
    void buildAtPose(const JointSolverView& view, Joint& joint);
  };

  // The joint's entry this step, or -1.
  std::int32_t entryAt(const Joint& joint) const {
    if (joints_ == nullptr) return -1;
    const std::size_t index = static_cast<std::size_t>(&joint - joints_);
    return index < entryOfJoint_.size() ? entryOfJoint_[index] : -1;
  }
  void buildLimitCandidates(const Entry& entry, const JointFrame& frame, Joint& joint);
  // The blocks and the right-hand side: G v + biasRate C for a velocity pass, C alone for the
  // projection. fillRightHandSide: the latter alone, where the blocks hold these rows' factor.
  bool fillTree(const JointSolverView& view, std::size_t first, std::size_t last, float biasRate,
                bool positions);
  void fillRightHandSide(std::size_t first, std::size_t last, float biasRate, bool positions);
  // Where a pass's blocks and right-hand side go: the tree's own (matrices_ and rhs_ at its nodes'
  // offsets and sizes), or one lane of its group's records (the group's offsets and sizes, every
  // kTreeLanes-th double from the lane's first).
  struct BlockLayout {
    double* matrices = nullptr;
    double* vectors = nullptr;
    const LaneNode* lanes = nullptr;  // the group's nodes, or null for the tree's own layout
  };
  struct NodeBlocks {
    double* d;
    double* coupling;
    double* vector;
    int size;        // as laid out
    int parentSize;  // the parent's, as laid out (the coupling's columns)
    std::size_t stride;
  };
  NodeBlocks blocksOf(const BlockLayout& layout, std::size_t first, std::size_t n) const;
  void setNodeSizes(std::size_t first, std::size_t last);  // this pass's, from the rows
  bool fillBlocks(const JointSolverView& view, std::size_t first, std::size_t last, bool positions,
                  const BlockLayout& layout);
  void fillRightHandSide(std::size_t first, std::size_t last, float biasRate, bool positions,
                         const BlockLayout& layout);
  enum class RowPass { WarmStart, SolveAtWarmStartPose, Solve };
  struct BuiltRows {
    bool tookLimit = false;  // a limit row is among them
    bool sameLimits = true;  // each joint took the limits its last pass ended with
  };
  // Tree t's rows for the pass.
  BuiltRows buildRows(const JointSolverView& view, Array<Joint>& joints, float h, RowPass pass,
                      std::size_t t);
  bool dropPullingLimits(Array<Joint>& joints, std::size_t first, std::size_t last, const Softness& soft);
  void addGeometricStiffness(const JointSolverView& view, Array<Joint>& joints, float h, std::size_t t);
  void solveTreePass(const JointSolverView& view, Array<Joint>& joints, float h, const Softness& soft,
                     bool useBias, std::size_t t);
  // Tree t's solves from `round` on (fill, factor unless the blocks hold it, solve, drop the pulling
  // limits, again): whether it solved.
  bool solveRounds(const JointSolverView& view, Array<Joint>& joints, const Softness& soft, std::size_t t,
                   const BuiltRows& built, bool factored, int round);
  // The pass's impulses of a solved tree applied, and its joints told whether it solved.
  void finishTreePass(Array<Joint>& joints, const Softness& soft, std::size_t t, bool solved);
  // The same pass for a group of trees of one shape, every round in lanes.
  struct TreeUnit;
  void solveGroupPass(const JointSolverView& view, Array<Joint>& joints, float h, const Softness& soft,
                      bool useBias, TreeUnit& unit);
  // A velocity pass's blocks (unless the lanes hold their factor) and right-hand sides of the
  // group's trees in `lanes` (a bit per lane); the lanes whose blocks could be filled.
  unsigned fillGroup(const JointSolverView& view, TreeUnit& unit, unsigned lanes, float biasRate,
                     bool factored);
  void copySolution(const TreeUnit& unit, std::uint32_t lane);
  // The projection's check (rows at the pose, and its limits where none is off) and its Newton step.
  bool rowsOff(const JointSolverView& view, Array<Joint>& joints, std::size_t t);
  void moveOntoRows(const JointSolverView& view, std::size_t t);
  bool sameShape(std::size_t t, std::size_t u) const;
  void groupTrees();
  void projectTree(const JointSolverView& view, Array<Joint>& joints, std::size_t t);
  // f(t) for every tree, in parallel ranges of trees.
  template <typename F>
  void forEachTree(TaskRunner& tasks, F&& f) {
    const std::uint32_t trees = static_cast<std::uint32_t>(treeStart_.size() - 1);
    tasks.parallelFor(trees, 1, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t t = begin; t < end; ++t) f(std::size_t{t});
    });
  }
  void buildTreeRows(const JointSolverView& view, Array<Joint>& joints, std::size_t first, std::size_t last);
  const Node* parentOf(const Node& node) const {
    return node.parent < 0 ? nullptr : &nodes_[static_cast<std::size_t>(node.parent)];
  }
  bool factorTree(std::size_t first, std::size_t last);
  void solveTree(std::size_t first, std::size_t last);
  // f(entry's rows, row, lambda) for every row of the tree's joints, lambda from the last solveTree.
  template <typename F>
  void forEachRow(std::size_t first, std::size_t last, F&& f) {
    for (std::size_t n = first; n < last; ++n) {
      const Node& node = nodes_[n];
      if (node.joint < 0) continue;
      EntryRows& passRows = entryRows_[static_cast<std::size_t>(node.joint)];
      const double* lambda = solution_.data() + node.vector + (node.body >= 0 ? 6 : 0);
      for (int i = 0; i < passRows.rows.count; ++i)
        f(passRows, passRows.rows.rows[static_cast<std::size_t>(i)], lambda[i]);
    }
  }

  // The trees as the solve passes take them: groups of kTreeLanes consecutive trees of one shape
  // (the same nodes, parents and capacities: a pile of ragdolls), factored and solved side by side
  // in lanes (joint_tree_lanes.h), and single trees.
  struct TreeUnit {
    std::uint32_t firstTree = 0;
    std::uint32_t treeCount = 1;     // 1, or kTreeLanes in lanes
    std::uint32_t nodeCount = 0;     // each tree's nodes (lanes only)
    std::uint32_t laneNodes = 0;     // its nodes' start in laneNodes_
    std::uint32_t laneMatrices = 0;  // its lane records' start in laneMatrices_ (records of 4 doubles)
    std::uint32_t laneVectors = 0;   // and in laneVectors_
    bool laneFactored = false;       // its lane blocks hold its trees' factor (as factored_ per tree)
    unsigned laneOk = 0;             // the lanes that factor left solvable
  };
  Array<TreeUnit> units_;
  Array<LaneNode> laneNodes_;
  Array<double> laneMatrices_;
  Array<double> laneVectors_;
  // A group's lane records: its blocks, and its right-hand side (then solution).
  double* laneMatricesOf(const TreeUnit& unit) {
    return laneMatrices_.data() + std::size_t{unit.laneMatrices} * kTreeLanes;
  }
  double* laneVectorsOf(const TreeUnit& unit) {
    return laneVectors_.data() + std::size_t{unit.laneVectors} * kTreeLanes;
  }

  float h_ = 0.0f;  // the substep of the last solve pass
  // frameAtPose's map: the step's joints, each joint's entry (-1 for none) and each entry's tree.
  const Joint* joints_ = nullptr;
  Array<std::int32_t> entryOfJoint_;
  Array<std::uint32_t> entryTree_;
  Array<Entry> entries_;
  Array<EntryRows> entryRows_;      // at least as many as entries_
  Array<Node> nodes_;               // per tree, in elimination order (leaves first, root last)
  Array<std::uint32_t> treeStart_;  // tree t's nodes: [treeStart_[t], treeStart_[t + 1])
  // Tree t's entries in entry order (the order their loads sum in): treeEntries_[treeEntryStart_[t]
  // .. treeEntryStart_[t + 1]).
  Array<std::uint32_t> treeEntries_;
  Array<std::uint32_t> treeEntryStart_;
  // Per tree: its entries' frames and equality rows are those of the bodies' current pose.
  Array<std::uint8_t> rowsAtPose_;
  // Per tree: its last pass solved it (its joints' inTree is true).
  Array<std::uint8_t> treeSolved_;
  // Per tree: the blocks hold the factor of its rows as they are, at the bodies' pose and with their
  // stiffness (the last velocity pass's).
  Array<std::uint8_t> factored_;
  // The limit rows each joint with limits could add, at the pose they were built at, and per tree
  // whether that is the bodies' pose still (a cone's twist is an atan2 each time it is built).
  Array<EqualityRows> limitCandidates_;
  Array<JointAngles> limitAngles_;  // by limit slot, the angles the candidates were built from
  Array<std::uint8_t> limitsAtPose_;
  Array<double> matrices_;
  Array<double> rhs_;
  Array<double> solution_;
  // prepare's scratch
  Array<std::int32_t> parentOf_;
  Array<std::int32_t> groundJoint_;
  Array<std::uint8_t> grounded_;       // per union-find root: the tree hangs from the ground
  Array<std::uint32_t> forestCounts_;  // per body, then per root: tree joints, loop joints
  Array<std::uint8_t> inMesh_;         // per body: its component is a mesh (Gauss-Seidel whole)
  Array<std::uint32_t> adjacencyStart_;
  Array<std::uint32_t> adjacency_;
  Array<std::int32_t> bodyNode_;
  // Per solver body of a tree: the inertia its loads add this pass, and its inverse inertia with it.
  Array<Mat3> addedInertia_;
  Array<Mat3> effectiveInverseInertia_;
  Array<Vec3> projectionTurn_;  // per solver body of a tree: the projection step's turn
};

}  // namespace collide::detail
