// The panel's editor for every WorldDef field (and the scene's time step). The viewer applies each
// edit to the running World (World::setDef), from its next step.
#pragma once

#include <collide/world.h>

namespace collide::viewer {

// Draws the widgets inside the current ImGui window; returns true when a value changed.
bool editWorldSettings(WorldDef& def, float& dt);

}  // namespace collide::viewer
