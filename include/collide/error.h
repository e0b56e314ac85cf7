// Errors at the API boundary. Constructors, builders and fitters validate their input and throw
// collide::Error with a message that names the problem and the offending value, e.g.
// "sphere: radius must be finite and > 0, got -1". World::step throws only for a bad dt, or once the
// step is complete for settings a pre-solve callback got wrong; a body whose state stops being finite
// during the step is frozen and reported instead (World::faultEvents).
#pragma once

#include <stdexcept>
#include <string>

namespace collide {

class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace collide
