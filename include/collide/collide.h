// collide: collision detection and response for 3D games. Include this for the whole public API.
#pragma once

#include <collide/body.h>
#include <collide/bounding.h>
#include <collide/broadphase.h>
#include <collide/character.h>
#include <collide/debug_draw.h>
#include <collide/error.h>
#include <collide/events.h>
#include <collide/joints.h>
#include <collide/math.h>
#include <collide/narrowphase.h>
#include <collide/queries.h>
#include <collide/settings.h>
#include <collide/shapes.h>
#include <collide/tasks.h>
#include <collide/version.h>
#include <collide/world.h>
