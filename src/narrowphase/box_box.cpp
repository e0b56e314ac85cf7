// Box against box: the separating-axis test specialised to two boxes, in A's local frame
// (Gottschalk, Lin and Manocha, "OBBTree", SIGGRAPH 1996, for the 15 axes; the contact as in
// sat_polyhedra.cpp, after Gregorius, GDC 2013 and 2015). It answers exactly what the generic
// polyhedron routine answers for two boxes (tested against it on random pairs) at a fraction of
// the cost: no vertex is transformed to the world, the 6 face axes cost a dot product each, the
// 9 edge axes replace the 12 × 12 Gauss-map edge pairs (for two boxes every pair of non-parallel
// edge directions makes two faces of the Minkowski difference, so the Gauss-map test always
// passes for the supporting edges), and the incident face is clipped against the reference
// face's side planes, which are axis-aligned in the reference box's frame.
//
// The decisions are the generic routine's: the same early-outs against the speculative margin,
// the same preference of a face over an edge pair (0.98 relative plus 1e-3 of the smaller box's
// size) and of the larger face between A's and B's, the same fallback to the deepest incident
// vertex, the same reduction to four points (reduceContacts).
//
// Feature ids use the box codes (pair_functions.h). A point where an incident edge crosses a side
// plane is named by (reference edge, incident edge); where a side of the clipped polygon runs along
// one side plane and crosses the next, by (reference corner, incident face). The names follow from
// digit arithmetic on the codes (merge: the smallest feature holding both; meet: the feature on
// both), so they do not depend on the order of the clipping planes, and a box resting on a box
// keeps (reference face, incident corner) for its four corners.
#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/closest_points.h"
#include "narrowphase/pair_functions.h"

namespace collide::detail {

namespace {

// ---- Box codes: three ternary digits dx + 3 dy + 9 dz (0 at -extent, 2 at +extent, 1 between). ----

constexpr int kPow3[3] = {1, 3, 9};

constexpr int digitOf(int code, int axis) { return (code / kPow3[axis]) % 3; }

// The smallest feature holding both: digits that differ become 1 (two corners of an edge give the
// edge, two edges of a face the face).
constexpr int mergeCodes(int a, int b) {
  int code = 0;
  for (int k = 0; k < 3; ++k) {
    const int da = digitOf(a, k), db = digitOf(b, k);
    code += (da == db ? da : 1) * kPow3[k];
  }
  return code;
}

// The feature lying on both: a 1 digit takes the other's digit (a face and one of its edges give
// the edge, two adjacent edges their common corner).
constexpr int meetCodes(int a, int b) {
  int code = 0;
  for (int k = 0; k < 3; ++k) {
    const int da = digitOf(a, k);
    code += (da == 1 ? digitOf(b, k) : da) * kPow3[k];
  }
  return code;
}

constexpr int signDigit(float s) { return s > 0.0f ? 2 : 0; }

// ---- The pair in a reference box's frame ----

// The other box seen from a reference box: its centre and axes (columns) in the reference frame.
struct Relative {
  Mat3 axes;
  Vec3 center;
};

struct ClipPoint {
  Vec3 position;      // reference frame
  int referenceCode;  // reference box feature
  int incidentCode;   // incident box feature
};

constexpr int kMaxClip = 12;  // a quad clipped by four planes has at most 8 vertices

// Keeps the part of the polygon where sign * x[axis] <= extent (Sutherland–Hodgman, one
// axis-aligned plane). A new vertex lies on the side plane named sideCode.
int clipAgainstSide(const ClipPoint* in, int count, int axis, float sign, float extent, int sideCode,
                    ClipPoint* out) {
  int kept = 0;
  if (count == 0) return 0;
  const ClipPoint* a = &in[count - 1];
  float distanceA = sign * a->position[axis] - extent;
  for (int i = 0; i < count; ++i) {
    const ClipPoint& b = in[i];
    const float distanceB = sign * b.position[axis] - extent;
    if ((distanceA <= 0.0f) != (distanceB <= 0.0f)) {
      const float t = distanceA / (distanceA - distanceB);
      out[kept++] = {a->position + t * (b.position - a->position),
                     meetCodes(mergeCodes(a->referenceCode, b.referenceCode), sideCode),
                     mergeCodes(a->incidentCode, b.incidentCode)};
    }
    if (distanceB <= 0.0f) out[kept++] = b;
    a = &b;
    distanceA = distanceB;
  }
  return kept;
}

// Whether the edges supporting A along `axis` (A's edge along e_i) and B against it (B's edge
// along R_j) make a face of the Minkowski difference: their arcs on the Gauss map cross (the test
// of sat_polyhedra.cpp, Gregorius 2013). It fails only where the axis is (nearly) a face normal
// and the arcs merely touch; the generic routine skips those pairs, and so must we to agree with
// it (for positive separations the face preference would otherwise pick the degenerate edge axis).
bool supportingEdgesCross(int i, int j, const Vec3& axis, const Mat3& R) {
  const int k = (i + 1) % 3, l = (i + 2) % 3;
  Vec3 a(0.0f), b(0.0f);
  a[k] = axis[k] >= 0.0f ? 1.0f : -1.0f;
  b[l] = axis[l] >= 0.0f ? 1.0f : -1.0f;
  const int m = (j + 1) % 3, n = (j + 2) % 3;
  // B's faces at its supporting edge face against the axis; negated for A - B.
  const Vec3 c = (glm::dot(axis, R[m]) > 0.0f ? 1.0f : -1.0f) * R[m];
  const Vec3 d = (glm::dot(axis, R[n]) > 0.0f ? 1.0f : -1.0f) * R[n];
  const Vec3 bxa = glm::cross(b, a);
  const Vec3 dxc = glm::cross(d, c);
  const float cba = glm::dot(c, bxa);
  const float dba = glm::dot(d, bxa);
  const float adc = glm::dot(a, dxc);
  const float bdc = glm::dot(b, dxc);
  return cba * dba < 0.0f && adc * bdc < 0.0f && cba * bdc > 0.0f;
}

// A placed frame: world = position + rotation * local (local in world units).
struct Frame {
  Mat3 rotation;
  Vec3 position;
};

// Writes one face-contact point: `p` is the incident point in the reference frame, `separation`
// its height over the reference face. The point on the reference face is the incident point moved
// down the normal, so each point costs one frame transform, not two.
inline void writeFacePoint(const ClipPoint& p, float separation, const Vec3& normal, const Frame& frame,
                           bool refIsA, ContactPoint& point) {
  const Vec3 worldIncident = frame.position + frame.rotation * p.position;
  const Vec3 worldReference = worldIncident - separation * normal;
  point.depth = -separation;
  const auto refCode = static_cast<std::uint32_t>(p.referenceCode);
  const auto incCode = static_cast<std::uint32_t>(p.incidentCode);
  if (refIsA) {
    point.pointOnA = worldReference;
    point.pointOnB = worldIncident;
    point.featureId = featurePair(refCode, incCode);
  } else {
    point.pointOnA = worldIncident;
    point.pointOnB = worldReference;
    point.featureId = featurePair(incCode, refCode);
  }
}

// More than four clipped points (a tilted face cut by the side planes): reduced to four as the
// generic routine does. Apart so that the common case does not initialise the candidates' array.
[[gnu::noinline]] void reduceFacePoints(const ClipPoint* in, int count, int axis, float sign,
                                        float planeOffset, const Vec3& normal, const Frame& frame,
                                        bool refIsA, float margin, Manifold& out) {
  std::array<ContactPoint, kMaxClip> candidates;
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    const float separation = sign * in[i].position[axis] - planeOffset;
    if (separation > margin) continue;
    writeFacePoint(in[i], separation, normal, frame, refIsA, candidates[kept++]);
  }
  reduceContacts(std::span<const ContactPoint>(candidates.data(), static_cast<std::size_t>(kept)), out.normal,
                 out);
}

// The incident box's corner deepest below the reference face (axis, sign), named for the reference
// face. Deep or skewed overlaps can leave no clipped point within the margin; this corner then stands
// for the contact, as in the generic routine.
ClipPoint deepestIncidentCorner(const Vec3& hi, const Relative& inc, int axis, float sign,
                                int referenceFace) {
  Vec3 p = inc.center;
  int code = 0;
  for (int m = 0; m < 3; ++m) {
    const float s = sign * inc.axes[m][axis] > 0.0f ? -1.0f : 1.0f;
    p += (s * hi[m]) * inc.axes[m];
    code += signDigit(s) * kPow3[m];
  }
  return {p, referenceFace, code};
}

// Face contact with the reference face (axis, sign) of the reference box (half extents hr) and
// the incident box (half extents hi) placed by `inc` in the reference frame (absAxes: |inc.axes|).
// Writes world points through `frame` (the reference box's); refIsA says which box is A.
bool faceContact(const Vec3& hr, const Vec3& hi, const Relative& inc, const Mat3& absAxes, int axis,
                 float sign, const Frame& frame, bool refIsA, float margin, Manifold& out) {
  // The incident face: the incident box's face most anti-parallel to the reference normal.
  int incAxis = 0;
  float best = absAxes[0][axis];
  if (absAxes[1][axis] > best) {
    best = absAxes[1][axis];
    incAxis = 1;
  }
  if (absAxes[2][axis] > best) incAxis = 2;
  const float incSign = sign * inc.axes[incAxis][axis] > 0.0f ? -1.0f : 1.0f;
  const int u = (incAxis + 1) % 3, v = (incAxis + 2) % 3;
  const Vec3 faceCenter = inc.center + (incSign * hi[incAxis]) * inc.axes[incAxis];
  const Vec3 du = hi[u] * inc.axes[u], dv = hi[v] * inc.axes[v];

  int referenceFace = kPow3[0] + kPow3[1] + kPow3[2];  // 13: all digits 1
  referenceFace += (signDigit(sign) - 1) * kPow3[axis];
  const int incidentFaceCode = signDigit(incSign) * kPow3[incAxis];
  const int plusU = 2 * kPow3[u], plusV = 2 * kPow3[v];
  std::array<ClipPoint, kMaxClip> bufferA, bufferB;
  // In order around the face.
  const Vec3 pu = faceCenter + du, mu = faceCenter - du;
  bufferA[0] = {pu + dv, referenceFace, incidentFaceCode + plusU + plusV};
  bufferA[1] = {mu + dv, referenceFace, incidentFaceCode + plusV};
  bufferA[2] = {mu - dv, referenceFace, incidentFaceCode};
  bufferA[3] = {pu - dv, referenceFace, incidentFaceCode + plusU};
  ClipPoint* in = bufferA.data();
  ClipPoint* next = bufferB.data();
  int count = 4;
  // A box resting inside the reference face needs no clipping: all four corners within its sides.
  const int k1 = (axis + 1) % 3, k2 = (axis + 2) % 3;
  bool inside = true;
  for (int i = 0; i < 4; ++i) {
    inside = inside && std::abs(in[i].position[k1]) <= hr[k1] && std::abs(in[i].position[k2]) <= hr[k2];
  }
  if (!inside) {
    for (int side = 1; side <= 2 && count > 0; ++side) {
      const int k = (axis + side) % 3;
      for (const float s : {1.0f, -1.0f}) {
        const int sideCode = referenceFace + (signDigit(s) - 1) * kPow3[k];
        count = clipAgainstSide(in, count, k, s, hr[k], sideCode, next);
        std::swap(in, next);
        if (count == 0) break;
      }
    }
  }

  const float planeOffset = hr[axis];
  std::array<float, kMaxClip> separations;
  bool anyWithin = false;
  for (int i = 0; i < count; ++i) {
    separations[i] = sign * in[i].position[axis] - planeOffset;
    anyWithin = anyWithin || separations[i] <= margin;
  }
  if (!anyWithin) {
    in[0] = deepestIncidentCorner(hi, inc, axis, sign, referenceFace);
    separations[0] = sign * in[0].position[axis] - planeOffset;
    count = 1;
  }

  const Vec3 normal = frame.rotation[axis] * sign;  // world, outward from the reference box
  out.normal = refIsA ? normal : -normal;
  if (count > Manifold::kMaxPoints) {
    reduceFacePoints(in, count, axis, sign, planeOffset, normal, frame, refIsA, margin, out);
    return out.count > 0;
  }
  // Up to four points go straight to the manifold (the resting case).
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    if (separations[i] > margin) continue;
    writeFacePoint(in[i], separations[i], normal, frame, refIsA, out.points[kept++]);
  }
  out.count = kept;
  return kept > 0;
}

// ---- The stages of collideBoxBox, all in A's frame ----

// The preference of a face over an edge pair and between faces, as in collidePolyhedra.
constexpr float kRelative = 0.98f;

// B in A's frame, computed once: R's column j is B's axis j (R = Aᵀ B), T is B's centre. Every
// axis of the test is read from R, |R| and T; nothing else is transformed.
struct BoxPair {
  Vec3 hA, hB;  // half extents, scaled
  Mat3 R, absR;
  Vec3 T;
};

BoxPair boxPairInFrameOf(const Frame& frameA, const Vec3& hA, const Vec3& hB, const Mat3& rotationB,
                         const Vec3& offset) {
  BoxPair pair{hA, hB, Mat3(), Mat3(), Vec3()};
  Mat3& R = pair.R;
  Mat3& absR = pair.absR;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      R[j][i] = glm::dot(frameA.rotation[i], rotationB[j]);
      absR[j][i] = std::abs(R[j][i]);
    }
  }
  pair.T = Vec3(glm::dot(frameA.rotation[0], offset), glm::dot(frameA.rotation[1], offset),
                glm::dot(frameA.rotation[2], offset));
  return pair;
}

// The deepest face axis of one box, or the first that separates beyond the margin.
struct FaceAxis {
  float separation = -1e30f;
  int axis = 0;
};

// 1. A's face axes: e_i. False as soon as an axis separates beyond the margin, since that ends the
// test (most apart pairs stop here, before anything else is computed).
bool deepestFaceOfA(const BoxPair& pair, float margin, FaceAxis& face) {
  const Vec3& hA = pair.hA;
  const Vec3& hB = pair.hB;
  const Mat3& absR = pair.absR;
  const Vec3& T = pair.T;
  for (int i = 0; i < 3; ++i) {
    const float rB = hB.x * absR[0][i] + hB.y * absR[1][i] + hB.z * absR[2][i];
    const float separation = std::abs(T[i]) - hA[i] - rB;
    if (separation > margin) return false;
    if (separation > face.separation) {
      face.separation = separation;
      face.axis = i;
    }
  }
  return true;
}

// 2. B's face axes: R's columns. False as soon as one separates beyond the margin, as for A's.
bool deepestFaceOfB(const BoxPair& pair, float margin, FaceAxis& face) {
  const Vec3& hA = pair.hA;
  const Vec3& hB = pair.hB;
  const Mat3& R = pair.R;
  const Mat3& absR = pair.absR;
  const Vec3& T = pair.T;
  for (int j = 0; j < 3; ++j) {
    const float rA = glm::dot(hA, absR[j]);
    const float separation = std::abs(glm::dot(T, R[j])) - hB[j] - rA;
    if (separation > margin) return false;
    if (separation > face.separation) {
      face.separation = separation;
      face.axis = j;
    }
  }
  return true;
}

// The reference face, as in collidePolyhedra: a face over a barely better edge pair, the larger
// face between two faces within the tolerance, so that collide(B, A) mirrors collide(A, B). True
// when it is B's.
bool referenceIsB(const BoxPair& pair, const FaceAxis& faceA, const FaceAxis& faceB, float absolute) {
  const Vec3& hA = pair.hA;
  const Vec3& hB = pair.hB;
  const float tolerance =
      (1.0f - kRelative) * std::max(std::abs(faceA.separation), std::abs(faceB.separation)) + absolute;
  bool isB = faceB.separation > faceA.separation;
  if (std::abs(faceA.separation - faceB.separation) <= tolerance) {
    const int a1 = (faceA.axis + 1) % 3, a2 = (faceA.axis + 2) % 3;
    const int b1 = (faceB.axis + 1) % 3, b2 = (faceB.axis + 2) % 3;
    const float areaA = hA[a1] * hA[a2], areaB = hB[b1] * hB[b2];
    if (std::abs(areaA - areaB) > 1e-4f * std::max(areaA, areaB)) isB = areaB > areaA;
  }
  return isB;
}

// The best edge axis that matters: e_i × B_j with the directions A's edge i and B's edge j.
struct EdgeAxis {
  float separation = -1e30f;  // stays -1e30 when no edge axis passes
  int edgeA = 0, edgeB = 0;
  Vec3 axis{0.0f};  // unit, from A towards B
};

// 3. Edge axes L = e_i × B_j, in closed form from R (Gottschalk et al. 1996, table 1): with b =
// B_j in A's frame, L = (…, -b[i2], b[i1]) has length sin(angle) = |(b[i1], b[i2])|, A's radius
// along it is hA[i1] |R_i2j| + hA[i2] |R_i1j|, B's is hB[j1] |R_ij2| + hB[j2] |R_ij1| (B's axes are
// right-handed: B_j × B_j1 = B_j2) and the centres are T[i2] R_i1j - T[i1] R_i2j apart along it.
// (Nearly) parallel edge directions are skipped as the generic routine does: their cross product
// has no direction, and the face axes cover that case. An edge axis matters only if it separates
// by more than the margin (apart) or is clearly better than the reference face (an edge contact);
// the separation stays scaled by |L| for that test (squared, no root) and only an axis that
// passes it is normalised. False as soon as an axis separates beyond the margin: nothing more to
// learn.
bool bestEdgeAxis(const BoxPair& pair, float margin, float edgeThreshold, EdgeAxis& edge) {
  const Vec3& hA = pair.hA;
  const Vec3& hB = pair.hB;
  const Mat3& R = pair.R;
  const Mat3& absR = pair.absR;
  const Vec3& T = pair.T;
  const float thresholdSquared = edgeThreshold * edgeThreshold;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const float bi1 = R[j][i1], bi2 = R[j][i2];
      const float lengthSquared = bi1 * bi1 + bi2 * bi2;
      if (lengthSquared < 1e-10f) continue;
      const float rA = hA[i1] * absR[j][i2] + hA[i2] * absR[j][i1];
      const float rB = hB[j1] * absR[j2][i] + hB[j2] * absR[j1][i];
      const float along = T[i2] * bi1 - T[i1] * bi2;
      const float scaledSeparation = std::abs(along) - rA - rB;
      // scaledSeparation <= edgeThreshold * |L|, without the root.
      const float bound = thresholdSquared * lengthSquared;
      const float scaledSquared = scaledSeparation * scaledSeparation;
      const bool below = edgeThreshold >= 0.0f ? (scaledSeparation <= 0.0f || scaledSquared <= bound)
                                               : (scaledSeparation < 0.0f && scaledSquared >= bound);
      if (below) continue;
      const float length = std::sqrt(lengthSquared);
      const float separation = scaledSeparation / length;
      if (separation <= edge.separation) continue;
      const float scale = (along < 0.0f ? -1.0f : 1.0f) / length;
      Vec3 towardsB;
      towardsB[i] = 0.0f;
      towardsB[i1] = -bi2 * scale;
      towardsB[i2] = bi1 * scale;
      if (!supportingEdgesCross(i, j, towardsB, R)) continue;
      if (separation > margin) return false;  // a separating axis: nothing more to learn
      edge.separation = separation;
      edge.edgeA = i;
      edge.edgeB = j;
      edge.axis = towardsB;
    }
  }
  return true;
}

// 4. Edge contact: the closest points of the supporting edges (A's along +axis, B's along -axis).
// False when they lie beyond the margin, and the face contact answers instead.
bool edgeContact(const BoxPair& pair, const EdgeAxis& edge, const Frame& frameA, float margin,
                 Manifold& out) {
  const Vec3& hA = pair.hA;
  const Vec3& hB = pair.hB;
  const Mat3& R = pair.R;
  const Vec3& edgeAxis = edge.axis;
  Vec3 centerA(0.0f);
  int codeA = kPow3[edge.edgeA];
  for (int k = 0; k < 3; ++k) {
    if (k == edge.edgeA) continue;
    const float s = edgeAxis[k] >= 0.0f ? 1.0f : -1.0f;
    centerA[k] = s * hA[k];
    codeA += signDigit(s) * kPow3[k];
  }
  Vec3 halfA(0.0f);
  halfA[edge.edgeA] = hA[edge.edgeA];
  Vec3 centerB = pair.T;
  int codeB = kPow3[edge.edgeB];
  for (int m = 0; m < 3; ++m) {
    if (m == edge.edgeB) continue;
    const float s = glm::dot(edgeAxis, R[m]) > 0.0f ? -1.0f : 1.0f;
    centerB += (s * hB[m]) * R[m];
    codeB += signDigit(s) * kPow3[m];
  }
  const Vec3 halfB = hB[edge.edgeB] * R[edge.edgeB];
  const SegmentPair closest =
      closestPointsSegmentSegment(centerA - halfA, centerA + halfA, centerB - halfB, centerB + halfB);
  const float depth = glm::dot(closest.pointOnFirst - closest.pointOnSecond, edgeAxis);
  if (!(depth >= -margin)) return false;
  ContactPoint& point = out.points[0];
  point.pointOnA = frameA.position + frameA.rotation * closest.pointOnFirst;
  point.pointOnB = frameA.position + frameA.rotation * closest.pointOnSecond;
  point.depth = depth;
  point.featureId = featurePair(static_cast<std::uint32_t>(codeA), static_cast<std::uint32_t>(codeB));
  out.normal = frameA.rotation * edgeAxis;
  out.count = 1;
  return true;
}

}  // namespace

bool collideBoxBox(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                   const Transform& transformB, float margin, Manifold& out) {
  out.count = 0;
  const Vec3 hA = shapeA.box().halfExtents * transformA.scale;
  const Vec3 hB = shapeB.box().halfExtents * transformB.scale;
  const Frame frameA{glm::mat3_cast(transformA.rotation), transformA.position};
  const Mat3 rotationB = glm::mat3_cast(transformB.rotation);
  const BoxPair pair = boxPairInFrameOf(frameA, hA, hB, rotationB, transformB.position - transformA.position);
  const Mat3& R = pair.R;
  const Vec3& T = pair.T;

  FaceAxis faceA, faceB;
  if (!deepestFaceOfA(pair, margin, faceA)) return false;
  if (!deepestFaceOfB(pair, margin, faceB)) return false;
  const float absolute = 1e-3f * std::min(glm::length(hA), glm::length(hB));
  const bool referenceB = referenceIsB(pair, faceA, faceB, absolute);
  const float faceSeparation = referenceB ? faceB.separation : faceA.separation;

  EdgeAxis edge;
  const float edgeThreshold = std::min(margin, kRelative * faceSeparation + absolute);
  if (!bestEdgeAxis(pair, margin, edgeThreshold, edge)) return false;
  if (edge.separation > kRelative * faceSeparation + absolute &&
      edgeContact(pair, edge, frameA, margin, out)) {
    return true;
  }

  if (referenceB) {
    // A seen from B: axes Rᵀ, centre -Rᵀ T. B's face on the side facing A.
    const Mat3 RT = glm::transpose(R);
    const Relative aInB{RT, -(RT * T)};
    const float sign = glm::dot(T, R[faceB.axis]) > 0.0f ? -1.0f : 1.0f;
    return faceContact(hB, hA, aInB, glm::transpose(pair.absR), faceB.axis, sign,
                       Frame{rotationB, transformB.position}, false, margin, out);
  }
  const float sign = T[faceA.axis] >= 0.0f ? 1.0f : -1.0f;
  return faceContact(hA, hB, Relative{R, T}, pair.absR, faceA.axis, sign, frameA, true, margin, out);
}

}  // namespace collide::detail
