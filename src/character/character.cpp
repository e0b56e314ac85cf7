// The character mover (collide/character.h, docs/character.md). The plane solver follows Box2D v3's
// mover (an accumulated push per plane, clamped at zero, so that a plane the others satisfy lets go
// and a corner settles instead of ping-ponging); the ground states, the steep-slope walls, the step
// up and the snap down follow Jolt's CharacterVirtual. Everything goes through the world's public
// queries: the mover is a user of the world like a game's own code.
#include <collide/character.h>
#include <collide/narrowphase.h>
#include <collide/world.h>

#include "base/fail.h"
#include "geometry/closest_points.h"
#include "geometry/triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace collide {

std::string_view toString(GroundState state) {
  switch (state) {
    case GroundState::OnGround:
      return "on ground";
    case GroundState::Sliding:
      return "sliding";
    case GroundState::InAir:
      return "in the air";
  }
  return "?";
}

namespace {

// Gauss-Seidel passes over the planes of one move, and the moves of one update.
constexpr int kSolverPasses = 20;
constexpr int kMoveIterations = 4;
// A move shorter than this is no move (m).
constexpr float kMinMove = 1e-5f;
// The planes a capsule keeps at most: the nearest, a flat floor's triangles alike merged first.
constexpr std::size_t kMaxPlanes = 64;

std::string formatNumber(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// The rotation that turns +y onto the unit vector `up` (the capsule's local axis onto up).
Quat rotationFromY(const Vec3& up) {
  const Vec3 y(0.0f, 1.0f, 0.0f);
  const float d = glm::dot(y, up);
  if (d < -0.999999f) return Quat(0.0f, 1.0f, 0.0f, 0.0f);  // upside down: half a turn about x
  return glm::normalize(Quat(1.0f + d, glm::cross(y, up)));
}

struct SegmentTriangle {
  Vec3 onSegment{0.0f};
  Vec3 onTriangle{0.0f};
  float distanceSquared = std::numeric_limits<float>::infinity();
};

// The closest points of segment [p, q] and triangle abc: an end of the segment against the face, an
// edge against the segment, or the point where the segment crosses the triangle.
SegmentTriangle closestSegmentTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                       const Vec3& c) {
  SegmentTriangle best;
  const auto consider = [&](const Vec3& onSegment, const Vec3& onTriangle) {
    const Vec3 d = onSegment - onTriangle;
    const float d2 = glm::dot(d, d);
    if (d2 < best.distanceSquared) best = {onSegment, onTriangle, d2};
  };
  consider(p, detail::closestPointOnTriangle(p, a, b, c).point);
  consider(q, detail::closestPointOnTriangle(q, a, b, c).point);
  for (const auto& [e0, e1] : {std::pair{a, b}, {b, c}, {c, a}}) {
    const detail::SegmentPair pair = detail::closestPointsSegmentSegment(p, q, e0, e1);
    consider(pair.pointOnFirst, pair.pointOnSecond);
  }
  // The segment through the face.
  const Vec3 n = detail::triangleAreaNormal(a, b, c);
  const float dp = glm::dot(n, p - a), dq = glm::dot(n, q - a);
  if ((dp < 0.0f) != (dq < 0.0f) && dp != dq) {
    const Vec3 x = p + (q - p) * (dp / (dp - dq));
    const Vec3 onFace = detail::closestPointOnTriangle(x, a, b, c).point;
    consider(x, onFace);
  }
  return best;
}

}  // namespace

namespace {

// The mover's solid: a capsule, or with a segment of length 0 (halfHeight 0, a crouch all the way
// down) the sphere that capsule is, which a Capsule refuses to be.
Shape bodyShape(float radius, float halfHeight) {
  if (halfHeight == 0.0f) return Shape(Sphere{radius});
  return Shape(Capsule{radius, halfHeight});
}

bool validCharacterDef(const CharacterDef& def) {
  const auto fail = [](const std::string& message) {
    detail::raiseError("character: " + message);
    return false;
  };
  if (!isFinite(def.position)) return fail("position must be finite");
  const float upLength = glm::length(def.up);
  if (!isFinite(def.up) || !(upLength > 1e-6f)) return fail("up must be a finite, non-zero direction");
  if (!(def.radius > 0.0f) || !std::isfinite(def.radius))
    return fail("radius must be finite and > 0, got " + formatNumber(def.radius));
  if (!(def.halfHeight >= 0.0f) || !std::isfinite(def.halfHeight))
    return fail("halfHeight must be finite and >= 0, got " + formatNumber(def.halfHeight));
  if (!(def.maxSlope > 0.0f && def.maxSlope < 0.5f * kPi))
    return fail("maxSlope must be in (0, pi/2) radians, got " + formatNumber(def.maxSlope));
  if (!(def.maxStepHeight >= 0.0f) || !std::isfinite(def.maxStepHeight))
    return fail("maxStepHeight must be finite and >= 0, got " + formatNumber(def.maxStepHeight));
  if (!(def.skinWidth > 0.0f) || !std::isfinite(def.skinWidth))
    return fail("skinWidth must be finite and > 0, got " + formatNumber(def.skinWidth));
  if (!(def.pushForce >= 0.0f) || !std::isfinite(def.pushForce))
    return fail("pushForce must be finite and >= 0, got " + formatNumber(def.pushForce));
  if (!(def.mass > 0.0f) || !std::isfinite(def.mass))
    return fail("mass must be finite and > 0, got " + formatNumber(def.mass));
  if (!isFinite(def.gravity)) return fail("gravity must be finite");
  return true;
}

}  // namespace

// Without exceptions a refused definition is reported and the default one taken.
Character::Character(const CharacterDef& def) : def_(validCharacterDef(def) ? def : CharacterDef{}) {
  def_.up = def_.up / glm::length(def_.up);
  position_ = def_.position;
}

void Character::setPosition(const Vec3& position, bool stop) {
  if (!isFinite(position)) COLLIDE_FAIL("character: setPosition: position must be finite");
  position_ = position;
  if (stop) {
    verticalSpeed_ = 0.0f;
    velocity_ = Vec3(0.0f);
  }
  groundState_ = GroundState::InAir;
  groundBody_ = BodyId{};
}

std::vector<Character::Plane> Character::planesNear(const World& world, const Vec3& position,
                                                    float margin) const {
  const Vec3 up = def_.up;
  const float radius = def_.radius;
  const Vec3 p = position - def_.halfHeight * up;
  const Vec3 q = position + def_.halfHeight * up;
  const Transform pose{position, rotationFromY(up), 1.0f};
  const Shape capsule = bodyShape(radius, def_.halfHeight);
  const Shape reach = bodyShape(radius + margin, def_.halfHeight);
  Aabb reachBox = worldBounds(reach, pose);

  std::vector<Plane> planes;
  const auto add = [&](BodyId body, const Vec3& normal, const Vec3& point, float gap,
                       const Vec3& surfaceNormal) {
    if (!(gap <= margin) || !isFinite(normal) || !isFinite(point)) return;
    // A flat floor's triangles give the same plane many times over: keep one (the nearest).
    for (Plane& plane : planes) {
      if (plane.body == body && glm::dot(plane.normal, normal) > 0.9999f &&
          std::abs(plane.gap - gap) < 1e-4f) {
        if (gap < plane.gap) plane.point = point, plane.gap = gap;
        return;
      }
    }
    const Vec3 r = point - world.centerOfMass(body);
    planes.push_back({body, normal, point, gap,
                      world.linearVelocity(body) + glm::cross(world.angularVelocity(body), r),
                      surfaceNormal});
  };
  // The surface's own normal under a contact point: a short ray down at it, from a little above and
  // a hair past the point away from the capsule (onto a step's top face, not off its edge). The
  // contact's normal when the ray finds nothing (a wall's point, which no ray from above reaches).
  const auto surfaceNormalAt = [&](const Shape& shape, const Transform& at, const Vec3& point,
                                   const Vec3& normal) {
    Vec3 away = -(normal - glm::dot(normal, up) * up);
    const float length = glm::length(away);
    away = length > 1e-4f ? away / length : Vec3(0.0f);
    constexpr float kAbove = 0.05f;
    const Ray ray{point + kAbove * up + 0.005f * away, -up, 2.0f * kAbove};
    const std::optional<RayHit> hit = rayCast(shape, at, ray);
    return hit && hit->distance > 0.0f ? hit->normal : normal;
  };
  // One part of a body: convex shapes and planes by the narrow phase's distance, meshes triangle by
  // triangle (a level's floor and wall are one mesh, but two planes), compounds child by child.
  const auto planesOf = [&](auto&& self, BodyId body, const Shape& shape, const Transform& at) -> void {
    switch (shape.type()) {
      case ShapeType::Mesh: {
        const TriangleMesh& mesh = shape.mesh();
        Aabb local = Aabb::empty();
        for (int corner = 0; corner < 8; ++corner) {
          const Vec3 c(corner & 1 ? reachBox.max.x : reachBox.min.x,
                       corner & 2 ? reachBox.max.y : reachBox.min.y,
                       corner & 4 ? reachBox.max.z : reachBox.min.z);
          local.grow(at.inverseApplyToPoint(c));
        }
        mesh.forEachTriangleOverlapping(local, [&](std::uint32_t index) {
          const std::array<Vec3, 3> t = mesh.triangle(index);
          const Vec3 a = at.applyToPoint(t[0]), b = at.applyToPoint(t[1]), c = at.applyToPoint(t[2]);
          const SegmentTriangle closest = closestSegmentTriangle(p, q, a, b, c);
          const float distance = std::sqrt(closest.distanceSquared);
          Vec3 normal;
          if (distance > 1e-6f) {
            normal = (closest.onSegment - closest.onTriangle) / distance;
          } else {
            // The segment touches the triangle: out along the face, to the side of the capsule's centre.
            const Vec3 face = detail::triangleAreaNormal(a, b, c);
            const float length = glm::length(face);
            if (!(length > 0.0f)) return;
            normal = face / length;
            if (glm::dot(normal, position - a) < 0.0f) normal = -normal;
          }
          // A mesh's surface normal is the triangle's own, turned to the capsule's side.
          Vec3 face = detail::triangleAreaNormal(a, b, c);
          const float faceLength = glm::length(face);
          face = faceLength > 0.0f ? face / faceLength : normal;
          if (glm::dot(face, normal) < 0.0f) face = -face;
          add(body, normal, closest.onTriangle, distance - radius, face);
        });
        break;
      }
      case ShapeType::Compound:
        for (const Compound::Child& child : shape.compound().children()) {
          const Transform childAt{at.applyToPoint(child.transform.position),
                                  at.rotation * child.transform.rotation, at.scale * child.transform.scale};
          self(self, body, child.shape, childAt);
        }
        break;
      default: {
        const DistanceResult d = distance(capsule, pose, shape, at);
        // normal runs from the capsule to the shape; the plane faces the capsule.
        if (!(d.distance <= margin)) break;
        add(body, -d.normal, d.pointOnB, d.distance, surfaceNormalAt(shape, at, d.pointOnB, -d.normal));
        break;
      }
    }
  };
  world.overlapShapeCollect(
      reach, pose,
      [&](const OverlapResult& overlap) {
        const Shape& shape = world.shape(overlap.body);
        const Transform at = world.transform(overlap.body);
        // A body made of parts is a compound of them: the part the query touched.
        if (shape.type() == ShapeType::Compound && overlap.part < shape.compound().children().size() &&
            world.partCount(overlap.body) > 1) {
          const Compound::Child& child = shape.compound().children()[overlap.part];
          const Transform childAt{at.applyToPoint(child.transform.position),
                                  at.rotation * child.transform.rotation, at.scale * child.transform.scale};
          planesOf(planesOf, overlap.body, child.shape, childAt);
        } else {
          planesOf(planesOf, overlap.body, shape, at);
        }
        return planes.size() < kMaxPlanes;
      },
      def_.filter);
  return planes;
}

float Character::castFraction(const World& world, const Vec3& from, const Vec3& displacement) const {
  if (glm::length(displacement) < kMinMove) return 1.0f;
  const Shape capsule = bodyShape(def_.radius, def_.halfHeight);
  const Transform pose{from, rotationFromY(def_.up), 1.0f};
  float fraction = 1.0f;
  world.castShapeCollect(
      capsule, pose, displacement,
      [&](const ShapeCastResult& hit) {
        // Surfaces the capsule starts touching are the planes' to handle: the sweep slides along them.
        if (hit.initiallyOverlapping) return 1.0f;
        fraction = std::min(fraction, hit.fraction);
        return fraction;
      },
      def_.filter);
  return fraction;
}

Character::MoveResult Character::move(World& world, const Vec3& from, const Vec3& displacement, bool record) {
  const float cosMaxSlope = std::cos(def_.maxSlope);
  const float skin = def_.skinWidth;
  MoveResult result{from, false};
  Vec3 remaining = displacement;
  // The first iteration runs even for no move: a surface that came into the capsule (a kinematic
  // body, a door) pushes it out.
  for (int iteration = 0;
       iteration < kMoveIterations && (iteration == 0 || glm::length(remaining) > kMinMove); ++iteration) {
    std::vector<Plane> planes = planesNear(world, result.position, skin + glm::length(remaining) + 0.01f);
    // A contact too steep to walk up is a wall for the walk as well: its horizontal normal keeps the
    // character from creeping up it by pushing into it (Jolt's steep-slope planes). That holds for a
    // step's edge too, whose contact leans however flat its top: steps are the step-up's to climb.
    const std::size_t surfaces = planes.size();
    for (std::size_t i = 0; i < surfaces; ++i) {
      const float rise = glm::dot(planes[i].normal, def_.up);
      if (rise <= 0.0f || rise >= cosMaxSlope) continue;
      const Vec3 across = planes[i].normal - rise * def_.up;
      const float length = glm::length(across);
      if (!(length > 1e-4f)) continue;
      Plane wall = planes[i];
      wall.normal = across / length;
      wall.gap = planes[i].gap / std::max(glm::dot(wall.normal, planes[i].normal), 0.1f);
      planes.push_back(wall);
    }
    // The move closest to the one asked that keeps the skin off every plane: each plane's push
    // accumulated and clamped at zero (a plane that no longer needs to push lets go).
    std::vector<float> push(planes.size(), 0.0f);
    Vec3 delta = remaining;
    for (int pass = 0; pass < kSolverPasses; ++pass) {
      float change = 0.0f;
      for (std::size_t i = 0; i < planes.size(); ++i) {
        const float separation = planes[i].gap + glm::dot(planes[i].normal, delta) - skin;
        const float next = std::max(0.0f, push[i] - separation);
        const float step = next - push[i];
        if (step == 0.0f) continue;
        delta += step * planes[i].normal;
        push[i] = next;
        change += std::abs(step);
      }
      if (change < 1e-6f) break;
    }
    for (std::size_t i = 0; i < planes.size(); ++i) {
      if (push[i] <= 0.0f && planes[i].gap > skin + 1e-3f) continue;
      if (glm::dot(planes[i].normal, def_.up) < cosMaxSlope && push[i] > 0.0f) result.blockedByWall = true;
      if (record && i < surfaces) touched_.push_back(planes[i]);
    }
    // The sweep: what the planes did not know of stops the move, a skin short of it.
    const float length = glm::length(delta);
    if (length < kMinMove) break;
    const float fraction = castFraction(world, result.position, delta);
    const float travelled = fraction >= 1.0f ? length : std::max(0.0f, fraction * length - skin);
    result.position += delta * (travelled / length);
    if (fraction >= 1.0f) break;
    remaining = delta * (1.0f - travelled / length);
  }
  return result;
}

// Jolt's stair walk: up by the step height (or what room there is), across as far as the walk asked,
// down onto the step's edge (ground by its surface), if the step's top is no higher than the step
// height and walkable.
std::optional<Vec3> Character::stepUp(World& world, const Vec3& start, const Vec3& across,
                                      const Vec3& walked) {
  const Vec3 up = def_.up;
  const float skin = def_.skinWidth;
  const float wanted = glm::length(across);
  const float rise =
      std::max(0.0f, castFraction(world, start, up * def_.maxStepHeight) * def_.maxStepHeight - skin);
  if (!(wanted > kMinMove) || !(rise > skin)) return std::nullopt;
  const Vec3 raised = start + rise * up;
  const auto dropOnto = [&](Vec3 position) -> std::optional<Vec3> {
    const float drop = glm::dot(position - start, up) + skin;
    if (!(drop > 0.0f)) return std::nullopt;
    const float down = castFraction(world, position, -up * drop);
    if (down >= 1.0f) return std::nullopt;
    position -= up * std::max(0.0f, down * drop - skin);
    const float climbed = glm::dot(position - start, up);
    if (climbed > def_.maxStepHeight + 1e-3f) return std::nullopt;
    return position;
  };
  const Vec3 direction = across / wanted;
  const std::optional<Vec3> stepped = dropOnto(move(world, raised, across, false).position);
  if (!stepped) return std::nullopt;
  // The step's top a little more than a radius past the landing (where the capsule is about to
  // stand, beyond the edge it touches): a ray down from
  // the raised feet finds it no higher than the step height, and walkable. Resting on the edge of a
  // step too high, the capsule's rounded bottom would otherwise count as standing on it.
  const Vec3 feet = *stepped - (def_.halfHeight + def_.radius) * up;
  const float startFeet = glm::dot(start - (def_.halfHeight + def_.radius) * up, up);
  // The ray starts a radius above the highest step allowed: one that starts inside something taller
  // hits it at once, at its own height, which is then too high.
  const float from = startFeet + def_.maxStepHeight + def_.radius;
  const Vec3 ahead = feet - glm::dot(feet, up) * up + from * up + direction * (def_.radius + 3.0f * skin);
  const std::optional<RayCastResult> top =
      world.castRay(Ray{ahead, -up, 2.0f * def_.maxStepHeight + def_.radius + skin}, def_.filter);
  if (!top || glm::dot(top->point, up) - startFeet > def_.maxStepHeight + 1e-3f ||
      glm::dot(top->normal, up) < std::cos(def_.maxSlope))
    return std::nullopt;
  const auto progress = [&](const Vec3& at) {
    const Vec3 gained = at - start;
    return glm::dot(gained - glm::dot(gained, up) * up, direction);
  };
  if (!(progress(*stepped) > progress(walked) + 1e-4f)) return std::nullopt;
  return stepped;
}

bool Character::overlapsAt(const World& world, const Vec3& position, float halfHeight) const {
  Character probe = *this;
  probe.def_.halfHeight = halfHeight;
  for (const Plane& plane : probe.planesNear(world, position, 0.0f)) {
    if (plane.gap < -0.25f * def_.skinWidth) return true;
  }
  return false;
}

void Character::findGround(const World& world) {
  const float cosMaxSlope = std::cos(def_.maxSlope);
  const Vec3 up = def_.up;
  const float bottom = glm::dot(position_ - def_.halfHeight * up, up);
  groundState_ = GroundState::InAir;
  groundBody_ = BodyId{};
  groundNormal_ = Vec3(0.0f);
  float bestRise = 0.0f;
  for (const Plane& plane : planesNear(world, position_, 2.0f * def_.skinWidth)) {
    const float rise = glm::dot(plane.normal, up);
    // Under the capsule's lower half-sphere, facing up, within the skin (and a little); walkable by
    // the surface's own slope (a step's edge under the capsule is its top face).
    if (rise <= 1e-3f || glm::dot(plane.point, up) > bottom + 1e-4f || plane.gap > 1.5f * def_.skinWidth)
      continue;
    const bool walkable = glm::dot(plane.surfaceNormal, up) >= cosMaxSlope;
    if (walkable && (groundState_ != GroundState::OnGround || rise > bestRise)) {
      groundState_ = GroundState::OnGround;
      bestRise = rise;
      groundBody_ = plane.body;
      groundNormal_ = plane.surfaceNormal;
    } else if (!walkable && groundState_ == GroundState::InAir) {
      groundState_ = GroundState::Sliding;
      groundBody_ = plane.body;
      groundNormal_ = plane.normal;
      bestRise = rise;
    }
  }
}

void Character::pushBodies(World& world, const Vec3& velocity, float dt) {
  const Vec3 up = def_.up;
  for (CharacterContact& contact : contacts_) {
    if (!world.isValid(contact.body) || world.type(contact.body) != BodyType::Dynamic) continue;
    const Vec3 into = -contact.normal;  // from the character into the body
    const Vec3 r = contact.point - world.centerOfMass(contact.body);
    const Vec3 bodyVelocity =
        world.linearVelocity(contact.body) + glm::cross(world.angularVelocity(contact.body), r);
    const float approach = glm::dot(velocity - bodyVelocity, into);
    if (contact.body == groundBody_) {
      // Standing on it: the character's weight.
      world.applyImpulse(contact.body, def_.mass * glm::dot(def_.gravity, up) * up * dt, contact.point);
      contact.pushed = true;
      continue;
    }
    if (!(approach > 0.0f) || def_.pushForce <= 0.0f) continue;
    // The body's velocity along the push brought to the character's, as far as the force allows; no
    // push down into what it stands on.
    Vec3 impulse = into * (approach * world.mass(contact.body));
    const float down = glm::dot(impulse, up);
    if (down < 0.0f) impulse -= down * up;
    const float most = def_.pushForce * dt;
    const float size = glm::length(impulse);
    if (size > most) impulse *= most / size;
    world.applyImpulse(contact.body, impulse, contact.point);
    contact.pushed = true;
  }
}

void Character::update(World& world, const Vec3& walkVelocity, float dt) {
  if (!(dt > 0.0f) || !std::isfinite(dt))
    COLLIDE_FAIL("character: update: dt must be finite and > 0, got " + formatNumber(dt));
  if (!isFinite(walkVelocity)) COLLIDE_FAIL("character: update: walkVelocity must be finite");
  const Vec3 up = def_.up;
  touched_.clear();
  contacts_.clear();

  // The ground's motion under the character over the step: its velocity, and the arc a turning
  // platform carries the character along (exact for a steady spin about its centre of mass).
  Vec3 carry(0.0f);
  groundVelocity_ = Vec3(0.0f);
  if (groundState_ == GroundState::OnGround && world.isValid(groundBody_) &&
      world.type(groundBody_) != BodyType::Static) {
    const Vec3 omega = world.angularVelocity(groundBody_);
    const Vec3 r = position_ - world.centerOfMass(groundBody_);
    const float angle = glm::length(omega) * dt;
    const Vec3 turned = angle > 0.0f ? glm::angleAxis(angle, omega / glm::length(omega)) * r : r;
    carry = world.linearVelocity(groundBody_) * dt + (turned - r);
    groundVelocity_ = carry / dt;
  }

  // The walk across up, along the ground's slope when standing; the part along up is a jump.
  const float jump = glm::dot(walkVelocity, up);
  Vec3 walk = walkVelocity - jump * up;
  const bool wasOnGround = groundState_ == GroundState::OnGround;
  if (wasOnGround && glm::length(walk) > 0.0f) {
    const Vec3 along = walk - glm::dot(walk, groundNormal_) * groundNormal_;
    const float length = glm::length(along);
    if (length > 1e-6f) walk = along * (glm::length(walk) / length);
  }
  if (jump > 0.0f) {
    verticalSpeed_ = jump;
  } else if (wasOnGround) {
    verticalSpeed_ = 0.0f;
  }
  if (groundState_ != GroundState::OnGround || jump > 0.0f) verticalSpeed_ += glm::dot(def_.gravity, up) * dt;
  const Vec3 displacement = (walk + verticalSpeed_ * up) * dt + carry;

  const Vec3 start = position_;
  MoveResult moved = move(world, start, displacement, true);
  // Stairs: a walk on the ground stopped by a wall tries up by the step height, across, and down.
  if (wasOnGround && jump <= 0.0f && moved.blockedByWall && def_.maxStepHeight > 0.0f) {
    const Vec3 across = walk * dt + carry - glm::dot(carry, up) * up;
    if (const std::optional<Vec3> stepped = stepUp(world, start, across, moved.position))
      moved.position = *stepped;
  }
  position_ = moved.position;
  findGround(world);
  // Down a step or over a bump: back onto walkable ground within the step height, unless rising.
  if (wasOnGround && groundState_ != GroundState::OnGround && jump <= 0.0f && def_.maxStepHeight > 0.0f) {
    const float reach = def_.maxStepHeight + def_.skinWidth;
    const float fraction = castFraction(world, position_, -up * reach);
    if (fraction < 1.0f) {
      const Vec3 saved = position_;
      position_ -= up * std::max(0.0f, fraction * reach - def_.skinWidth);
      findGround(world);
      if (groundState_ != GroundState::OnGround) {
        position_ = saved;
        findGround(world);
      }
    }
  }
  if (groundState_ == GroundState::OnGround) {
    verticalSpeed_ = 0.0f;
  } else {
    // A ceiling stops the rise: no more upward speed than the move made.
    const float rose = glm::dot(position_ - start - carry, up) / dt;
    if (verticalSpeed_ > 0.0f && rose < verticalSpeed_) verticalSpeed_ = std::max(0.0f, rose);
  }
  velocity_ = (position_ - start) / dt;

  // Each body touched once, its deepest contact; the ground among them.
  for (const Plane& plane : touched_) {
    auto found = std::find_if(contacts_.begin(), contacts_.end(),
                              [&](const CharacterContact& c) { return c.body == plane.body; });
    if (found == contacts_.end()) {
      contacts_.push_back({plane.body, plane.point, plane.normal, false});
    }
  }
  if (groundState_ == GroundState::OnGround && world.isValid(groundBody_) &&
      std::none_of(contacts_.begin(), contacts_.end(),
                   [&](const CharacterContact& c) { return c.body == groundBody_; })) {
    contacts_.push_back({groundBody_, footPosition(), groundNormal_, false});
  }
  // Bodies are pushed by the walk the character meant (the move they blocked would read as none).
  pushBodies(world, (displacement - carry) / dt, dt);
}

bool Character::setHalfHeight(World& world, float halfHeight) {
  if (!(halfHeight >= 0.0f) || !std::isfinite(halfHeight))
    COLLIDE_FAIL(
        "character: setHalfHeight: halfHeight must be finite and >= 0, got " + formatNumber(halfHeight),
        false);
  const Vec3 feet = footPosition();
  const Vec3 centre = feet + (halfHeight + def_.radius) * def_.up;
  if (halfHeight > def_.halfHeight && overlapsAt(world, centre, halfHeight)) return false;
  def_.halfHeight = halfHeight;
  position_ = centre;
  return true;
}

}  // namespace collide
