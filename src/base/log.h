// The library's messages to the engine (collide/hooks.h, setLogHandler): built only when a handler
// listens, so that a silent engine pays a pointer load.
#pragma once

#include <collide/hooks.h>

#include <string>

namespace collide::detail {

bool logging();
void logMessage(LogLevel level, const std::string& message);

// log(level, [&] { return std::string(...); }): the message is made only if someone listens.
template <typename MakeMessage>
void log(LogLevel level, MakeMessage&& makeMessage) {
  if (logging()) logMessage(level, makeMessage());
}

}  // namespace collide::detail
