// The panel's editor for every WorldDef field (and the scene's time step). The World fixes its
// WorldDef when it is created, so the edits take effect when the viewer rebuilds the World from the
// scene with them (Restart); the panel says so.
#pragma once

#include <collide/world.h>

namespace collide::viewer {

// Draws the widgets inside the current ImGui window; returns true when a value changed.
bool editWorldSettings(WorldDef& def, float& dt);

}  // namespace collide::viewer
