// Reading a whole input file as text, for the scene and OBJ loaders: only a regular file (a symbolic
// link to one too) no larger than the caller's limit is read, so that a directory, a device such as
// /dev/zero, a FIFO or a huge file is refused with a message instead of a hang or exhausted memory.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace collide::scene {

// The file's bytes. Throws collide::Error("WHO: ...") when it does not exist, is not a regular file
// or holds more than `maxBytes` bytes (checked before reading and again while reading, for a file
// that grows or whose size the file system does not report, as in /proc).
std::string readFileText(const std::filesystem::path& path, std::uintmax_t maxBytes, const std::string& who);

}  // namespace collide::scene
