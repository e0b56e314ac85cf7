// The registry of built-in scenes. Each generator returns the scene as JSON; `collide run NAME`
// reads that document as parseScene reads a file's (readSceneDocument), without its text.
#include <collide/scene/builtin_scenes.h>

#include "builtin_scene_parts.h"
#include "scene_document.h"

#include <functional>

namespace collide::scene {

namespace builtin {
Json billiards();
Json pile();
Json rain(double jitter);
Json pyramid();
Json terrain();
Json proxies();
Json penetrationDrop(const char* response);
Json breakable();
Json chain();
Json tunneling();
Json pendulum();
Json bridge();
Json ragdolls();
Json machine();
Json jointGrid();
Json ragdollPile();
Json largePile();
Json character();
}  // namespace builtin

namespace {

struct Entry {
  BuiltinScene scene;
  std::function<nlohmann::json()> generate;
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {{"billiards", "B1: the lecture's break shot, 16 balls on a table with cushions (the default)"},
       builtin::billiards},
      {{"pile", "R1: 4,096 unit cubes in a 16x16x16 lattice falling on the ground"}, builtin::pile},
      {{"rain", "R2: 8,000 spheres falling into an open container"}, [] { return builtin::rain(0.0); }},
      {{"rain-jittered", "R2 with each sphere moved by up to 4 cm sideways, so that the columns topple"},
       [] { return builtin::rain(0.04); }},
      {{"pyramid", "R3: a 30-row pyramid of 465 touching unit cubes"}, builtin::pyramid},
      {{"terrain", "R4: 2,000 convex hulls falling on a 100x100 sine-terrain mesh"}, builtin::terrain},
      {{"proxies", "three of every droppable proxy type falling on a plane, a mesh ramp and each other"},
       builtin::proxies},
      {{"revert", "a fast drop of boxes and spheres, penetration response revert"},
       [] { return builtin::penetrationDrop("revert"); }},
      {{"revert-project", "the same drop as revert, penetration response project"},
       [] { return builtin::penetrationDrop("project"); }},
      {{"revert-soft", "the same drop as revert, penetration response soft (the default)"},
       [] { return builtin::penetrationDrop("soft"); }},
      {{"breakable", "a brick wall whose bricks break under contact impulses, hit by a heavy ball"},
       builtin::breakable},
      {{"chain", "particles and distance constraints: a swinging rope and a net falling over a ball"},
       builtin::chain},
      {{"tunneling", "fast small bodies at thin plates, the same shots with ccd on and off"},
       builtin::tunneling},
      {{"pendulum", "a hinged rod pendulum and a 50-link ball-joint chain released level"},
       builtin::pendulum},
      {{"bridge", "40 planks on hinges between two posts, carrying a 50 kg crate"}, builtin::bridge},
      {{"ragdolls", "eight ragdolls (11 bodies, cone and hinge joints) thrown down a flight of stairs"},
       builtin::ragdolls},
      {{"machine", "a motorised windmill of welded blades batting balls, and a lift on a motorised slider"},
       builtin::machine},
      {{"joint-grid", "Box3D's joint_grid: 10,000 spheres in a 100x100 grid of ball joints, hanging"},
       builtin::jointGrid},
      {{"ragdoll-pile", "100 ragdolls (1,100 bodies, 1,000 joints) dropped into a pile"},
       builtin::ragdollPile},
      {{"character",
        "a player walked up stairs, down a ramp, through crates, over a kerb, onto a turning disc"},
       builtin::character},
      {{"large-pile", "100,000 unit cubes in a 100x10x100 lattice, the lowest layer on the ground"},
       builtin::largePile},
  };
  return entries;
}

const Entry& find(std::string_view name) {
  for (const Entry& e : registry()) {
    if (e.scene.name == name) return e;
  }
  std::string names;
  for (const Entry& e : registry()) names += (names.empty() ? "" : ", ") + std::string(e.scene.name);
  throw Error("unknown scene \"" + std::string(name) + "\": not a file and not a built-in scene (" + names +
              ")");
}

}  // namespace

std::vector<BuiltinScene> builtinScenes() {
  std::vector<BuiltinScene> out;
  for (const Entry& e : registry()) out.push_back(e.scene);
  return out;
}

bool isBuiltinScene(std::string_view name) {
  for (const Entry& e : registry()) {
    if (e.scene.name == name) return true;
  }
  return false;
}

std::string builtinSceneJson(std::string_view name) { return find(name).generate().dump(1) + "\n"; }

Scene loadBuiltinScene(std::string_view name) {
  // The generated document is read as it is, without its text and a second document parsed from
  // that (R4's three together took 16 MB, as much as its world after 600 steps); what the text would
  // have changed is the integers' kind (normalizeIntegers). Doubles print and parse back exactly.
  nlohmann::json document = find(name).generate();
  normalizeIntegers(document);
  return readSceneDocument(document, "builtin:" + std::string(name));
}

}  // namespace collide::scene
