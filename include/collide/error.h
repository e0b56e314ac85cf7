// Errors at the API boundary. Constructors, builders and fitters validate their input and throw
// collide::Error with a message that names the problem and the offending value, e.g.
// "sphere: radius must be finite and > 0, got -1". Inside the step, invariants are asserts.
#pragma once

#include <stdexcept>
#include <string>

namespace collide {

class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace collide
