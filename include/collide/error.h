// Errors at the API boundary. Constructors, builders, fitters and the world's functions validate
// their input and report what is wrong with a message that names the problem and the offending
// value, e.g. "sphere: radius must be finite and > 0, got -1".
//
// How the message reaches the caller depends on how the library was built (docs/integration.md,
// "Errors without exceptions"):
// - COLLIDE_EXCEPTIONS=ON (the default): a collide::Error is thrown, and nothing has changed.
// - COLLIDE_EXCEPTIONS=OFF (-fno-exceptions -fno-rtti): the error handler gets the message, it is
//   kept as lastError() for the thread, nothing has changed, and the function returns a result that
//   says so: a null BodyId or JointId, an empty ConvexHull or TriangleMesh (isEmpty()), a null
//   World from World::create, no hit, or an unchanged value. A Shape made from a bad primitive
//   carries the bad value and is refused, with the error again, by whatever uses it.
//
// Either way World::step reports only a bad dt, or once the step is complete, settings a pre-solve
// callback got wrong; a body whose state stops being finite during the step is frozen and reported
// instead (World::faultEvents).
#pragma once

#include <stdexcept>
#include <string>

namespace collide {

class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Whether this build throws Error (COLLIDE_EXCEPTIONS=ON) or reports through the error handler.
bool exceptionsEnabled();

// The engine's error handler, for builds without exceptions: called once per failed call with the
// full message (valid until the handler returns), on the thread that made the call. nullptr restores
// the default, which writes "collide: error: <message>" to stderr. A build with exceptions throws
// instead and does not call it.
using ErrorHandler = void (*)(const char* message, void* context);
void setErrorHandler(ErrorHandler handler, void* context = nullptr);

// The message of the last error reported on this thread in a build without exceptions, or "" if
// there was none since the last clearLastError().
const char* lastError();
void clearLastError();

}  // namespace collide
