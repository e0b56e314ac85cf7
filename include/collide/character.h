// A character that walks: the kinematic capsule mover a game moves its player and its NPCs with
// (docs/character.md). It is not a body of the world: each update it asks the world where its
// surfaces are (World::overlapShapeCollect, World::castShapeCollect), moves the capsule by the
// velocity the game asks for, sliding along what it meets, and tells the game where it stands.
// What it touches that is dynamic it pushes (World::applyImpulse); what moves into it (a kinematic
// platform, a door) pushes it.
//
// The motion of one update (Character::update):
//   1. the velocity: the game's walking velocity across `up`, plus the ground's velocity at the
//      character (a moving or turning platform carries it), plus its own vertical velocity
//      (gravity while not standing, a jump);
//   2. the move, in a few iterations: the surfaces near the capsule as planes, the move projected so
//      that it keeps off every plane by the skin (Gauss-Seidel over the planes, each push clamped as
//      it accumulates, so that corners and creases settle), a sweep that stops it at the first
//      surface, the rest slid along the planes it met;
//   3. stairs: a move blocked by a wall no higher than maxStepHeight goes up, across and down;
//   4. the ground: standing on a walkable surface (no steeper than maxSlope), sliding on a steeper
//      one, or in the air; walking off an edge or down a step snaps it back to the ground below
//      when that is within maxStepHeight.
#pragma once

#include <collide/body.h>
#include <collide/math.h>
#include <collide/queries.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace collide {

class World;

struct CharacterDef {
  // The capsule's centre, and the up direction (unit): the capsule stands along it, and "ground" is
  // what is below along it. Gravity is the world's, along -up unless given.
  Vec3 position{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float radius = 0.3f;      // m, > 0
  float halfHeight = 0.6f;  // m, >= 0: half the length of the capsule's segment (the total height is
                            // 2 (halfHeight + radius))
  // Surfaces up to this steep are walkable; steeper ones are walls and slides (radians, in (0, pi/2)).
  float maxSlope = 45.0f * kPi / 180.0f;
  // Steps up to this high are climbed, and drops up to this deep followed (m, >= 0).
  float maxStepHeight = 0.35f;
  // The gap kept between the capsule and every surface (m, > 0): a character resting on the floor
  // floats this high above it, so that the next sweep starts clear of it.
  float skinWidth = 0.02f;
  // Dynamic bodies in the way are pushed with at most this force (N, >= 0; 0 pushes nothing), as a
  // body of this mass (kg, > 0) would push them.
  float pushForce = 500.0f;
  float mass = 80.0f;
  // Gravity's acceleration while the character is not standing (m/s^2, finite).
  Vec3 gravity{0.0f, -9.81f, 0.0f};
  // What the character collides with (layers, sensors left out, a callback).
  QueryFilter filter{};
};

enum class GroundState : std::uint8_t {
  OnGround,  // on a walkable surface: it stands, carried by the surface's motion
  Sliding,   // touching only surfaces steeper than maxSlope below it: gravity slides it down them
  InAir,     // nothing below within the skin
};
// "on ground", "sliding", "in the air".
std::string_view toString(GroundState state);

// A surface the character touched during an update (the contact events of a character).
struct CharacterContact {
  BodyId body;
  Vec3 point{0.0f};     // on the body's surface
  Vec3 normal{0.0f};    // unit, from the surface towards the character
  bool pushed = false;  // the character gave the body an impulse (a dynamic body it walked into)
};

class Character {
 public:
  // Throws collide::Error naming the field for a definition out of range.
  explicit Character(const CharacterDef& def);

  // One update of dt seconds (> 0): walks at `walkVelocity` (its part across `up`; the part along
  // up, if any, is added to the character's own vertical velocity: a jump), then settles its ground
  // state. Call it after World::step, with the same dt, so that the ground's motion is the step's.
  void update(World& world, const Vec3& walkVelocity, float dt);

  Vec3 position() const { return position_; }
  // The capsule's lowest point (its feet).
  Vec3 footPosition() const { return position_ - (def_.halfHeight + def_.radius) * def_.up; }
  // The character's own velocity after the last update (the move it made, over dt).
  Vec3 velocity() const { return velocity_; }
  // Teleports it (a respawn). Its vertical velocity is kept unless `stop`.
  void setPosition(const Vec3& position, bool stop = true);

  GroundState groundState() const { return groundState_; }
  bool isOnGround() const { return groundState_ == GroundState::OnGround; }
  // The surface below (OnGround or Sliding): its body, its normal (unit, up-facing) and the velocity
  // of its point under the character (a platform's motion). Null body and zero velocity in the air.
  BodyId groundBody() const { return groundBody_; }
  Vec3 groundNormal() const { return groundNormal_; }
  Vec3 groundVelocity() const { return groundVelocity_; }

  // What the capsule touched in the last update, each body once (its deepest contact).
  std::span<const CharacterContact> contacts() const { return contacts_; }

  // A new height for the capsule (crouch and stand), keeping its feet where they are. Refused (false,
  // nothing changes) when the new capsule would overlap a surface, as standing up under a low
  // ceiling would. A halfHeight < 0 throws Error.
  bool setHalfHeight(World& world, float halfHeight);
  float halfHeight() const { return def_.halfHeight; }
  float radius() const { return def_.radius; }
  const CharacterDef& def() const { return def_; }

  // The plane of one surface near the capsule, as the mover sees it (for tests and drawing): its
  // normal (from the surface towards the capsule), the gap between the surface and the capsule
  // (negative: overlapping) and the closest point on the surface.
  struct Plane {
    BodyId body;
    Vec3 normal{0.0f};
    Vec3 point{0.0f};
    float gap = 0.0f;
    Vec3 bodyVelocity{0.0f};  // of the surface's point
    // The surface's own normal at the point (a face's, where the contact's normal leans off an edge
    // or a corner): what decides whether it can be walked on. A step's top edge is walkable ground
    // for a capsule that rests half over it.
    Vec3 surfaceNormal{0.0f};
  };
  // The surfaces within `margin` of the capsule at `position`.
  std::vector<Plane> planesNear(const World& world, const Vec3& position, float margin) const;

 private:
  struct MoveResult {
    Vec3 position;
    bool blockedByWall = false;  // a surface steeper than maxSlope stopped the walk
  };
  MoveResult move(World& world, const Vec3& from, const Vec3& displacement, bool record);
  float castFraction(const World& world, const Vec3& from, const Vec3& displacement) const;
  bool overlapsAt(const World& world, const Vec3& position, float halfHeight) const;
  std::optional<Vec3> stepUp(World& world, const Vec3& start, const Vec3& across, const Vec3& walked);
  void findGround(const World& world);
  void pushBodies(World& world, const Vec3& velocity, float dt);

  CharacterDef def_;
  Vec3 position_{0.0f};
  Vec3 velocity_{0.0f};
  float verticalSpeed_ = 0.0f;  // along up: gravity and jumps
  GroundState groundState_ = GroundState::InAir;
  BodyId groundBody_;
  Vec3 groundNormal_{0.0f};
  Vec3 groundVelocity_{0.0f};
  std::vector<CharacterContact> contacts_;
  std::vector<Plane> touched_;  // the planes the last move met, for the pushes
};

}  // namespace collide
