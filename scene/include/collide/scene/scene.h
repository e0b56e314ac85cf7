// Scene files (format "collide-scene/1", docs/scene-format.md): one JSON document describing the
// world's settings, materials, bodies and constraints. parseScene turns the text into a Scene,
// validating every field (an error names the field path and the value, e.g.
// "bodies[3].shape.radius: must be > 0, got -1"); buildWorld turns a Scene into a World.
#pragma once

#include <collide/character.h>
#include <collide/world.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

inline constexpr std::string_view kFormat = "collide-scene/1";

struct Material {
  std::optional<float> bounciness;
  std::optional<float> friction;
  std::optional<float> density;
  std::optional<float> rollingResistance;  // m
  friend bool operator==(const Material&, const Material&) = default;
};

struct Body {
  // The resolved definition: the body's own values over its material's over the engine defaults.
  // The shape is built (hulls, meshes and OBJ files already processed).
  BodyDef def;
  std::string material;  // empty when none
  // Our extension: a breakable body is removed once the contact impulses it received (the
  // impulses of its contact begin events, N s) add up to more than this (see runner.h).
  std::optional<float> breakImpulse;
};

// A constraint of the scene file's "constraints" (scene-format.md): its type's fields are set, the
// others keep their defaults.
struct Constraint {
  JointType type = JointType::Distance;
  std::string name;  // for events; empty: none given
  std::string a;
  std::string b;
  // distance
  std::optional<Vec3> anchorA;  // local points; unset: the centre of mass
  std::optional<Vec3> anchorB;
  std::optional<float> length;  // default: the distance at load time
  float compliance = 0.0f;      // 0 = rigid
  // ball, hinge, slider, cone (required), fixed (optional: b's centre): world frame at load time
  std::optional<Vec3> anchor;
  Vec3 axis{1.0f, 0.0f, 0.0f};  // hinge, slider, cone
  JointLimits limits;           // hinge, slider, distance (lengths); the cone's twist
  JointMotor motor;             // hinge, slider
  float swing = kPi;            // cone
  // stiffness (Hz) and damping (ratio): the joint's softness; a distance joint's spring
  JointSoftness softness;
  float breakForce = kUnbreakable;
  float breakTorque = kUnbreakable;
  float friction = 0.0f;  // ball, cone, hinge: N m; slider: N
  // false: a and b do not collide with each other (the default of every type but distance, which
  // keeps the scene format's first meaning: true)
  bool collideConnected = true;
};

// A character (collide/character.h) the runner walks along a path: to each waypoint in turn, across
// the up direction, at its speed; a waypoint with a jump speed jumps on the way to it.
struct SceneCharacter {
  std::string name;
  CharacterDef def;
  struct Waypoint {
    Vec3 to{0.0f};
    float speed = 2.0f;  // m/s, > 0
    float jump = 0.0f;   // m/s up when setting off towards it, >= 0
  };
  std::vector<Waypoint> path;
};

// Walks a scene character along its path: the velocity towards the next waypoint (a jump added once,
// from the ground), moving on as each is reached. `collide run` and the viewer share it.
class CharacterPath {
 public:
  explicit CharacterPath(const SceneCharacter& character) : character_(&character) {}
  // The walk velocity for this update (zero once the path is done).
  Vec3 nextVelocity(const Character& character, float dt);
  std::size_t reached() const { return next_; }
  bool done() const { return next_ >= character_->path.size(); }

 private:
  const SceneCharacter* character_;
  std::size_t next_ = 0;
  bool jumped_ = false;
};

struct Scene {
  std::string source;  // the file name or "builtin:NAME", prefixed to error messages
  // The files the scene was read from: the scene file (empty for a built-in or a parsed text) and
  // the OBJ files its meshes read, as the paths that were opened. `collide run` refuses to write an
  // output over any of them.
  std::filesystem::path file;
  std::vector<std::filesystem::path> objFiles;
  WorldDef world;  // gravity, substeps, broad phase, combine rules, models
  float dt = 1.0f / 60.0f;
  int steps = 600;
  std::map<std::string, Material> materials;
  std::vector<Body> bodies;
  std::vector<Constraint> constraints;
  std::vector<SceneCharacter> characters;
};

struct LoadOptions {
  // OBJ files ("file" of a mesh shape) are paths relative to the scene's folder and must stay inside
  // it: an absolute path, a ".." that climbs out or a symbolic link that leads out is refused, so
  // that a scene cannot read files elsewhere. True lifts that (`collide run --allow-outside-paths`).
  bool allowOutsidePaths = false;
};

// Parses a scene document. `baseDir` is the scene's folder, which resolves (and holds) its OBJ
// paths; `source` prefixes error messages. Throws collide::Error: malformed JSON (with line and
// column and the JSON parser's explanation), a key given twice in one object, nesting deeper than
// the limits, a wrong type, a missing required field, an unknown field or name, an out-of-range
// value, an OBJ file outside `baseDir` or one that readObjFile refuses. The limits are in
// collide/scene/limits.h.
Scene parseScene(std::string_view text, std::string_view source = "scene",
                 const std::filesystem::path& baseDir = ".", const LoadOptions& options = {});
// Reads and parses a scene file (OBJ paths relative to the file's folder). Also throws when the path
// is not a regular file (a directory, a device, a FIFO) or is larger than kMaxSceneFileBytes.
Scene loadSceneFile(const std::filesystem::path& path, const LoadOptions& options = {});

// One shape as a scene file writes a body's "shape" ({"type": "box", "halfExtents": [1, 2, 3]}, a
// hull's points, a mesh's OBJ file, a compound's children), validated as in a scene: the same errors,
// with `source` in front. `baseDir` resolves (and holds) a mesh's OBJ file. For `collide query`.
Shape parseShape(std::string_view text, std::string_view source = "shape",
                 const std::filesystem::path& baseDir = ".", const LoadOptions& options = {});
// Reads and parses a shape file (an OBJ path relative to the file's folder).
Shape loadShapeFile(const std::filesystem::path& path, const LoadOptions& options = {});

// A World built from a scene; bodies[i] is the id of scene.bodies[i], constraints[i] of
// scene.constraints[i].
struct SceneWorld {
  World world;
  std::vector<BodyId> bodies;
  std::vector<JointId> constraints;
};
// Throws collide::Error naming the field for what the World refuses ("constraints[2]: distance
// constraint: a and b: at least one body must be dynamic, ...").
SceneWorld buildWorld(const Scene& scene);

// The heap a loaded scene holds while its world runs, in bytes: its bodies' and constraints'
// definitions with their names, materials and file names, and the SceneWorld's id arrays. The
// shapes are shared with the world and not counted (as in WorldMemory).
std::size_t sceneMemoryBytes(const Scene& scene, const SceneWorld& world);

}  // namespace collide::scene
