// Input files for the loaders: regular files within a size limit, read whole.
#include "file_text.h"

#include <collide/error.h>

#include <fstream>
#include <system_error>

namespace collide::scene {

namespace {

std::string bytesText(std::uintmax_t bytes) {
  std::string text = std::to_string(bytes) + " bytes";
  if (bytes >= (1ull << 20) && bytes % (1ull << 20) == 0)
    text += " (" + std::to_string(bytes >> 20) + " MiB)";
  return text;
}

}  // namespace

std::string readFileText(const std::filesystem::path& path, std::uintmax_t maxBytes, const std::string& who) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);  // follows symbolic links
  if (status.type() == fs::file_type::not_found) throw Error(who + ": cannot be read: no such file");
  if (error) throw Error(who + ": cannot be read: " + error.message());
  switch (status.type()) {
    case fs::file_type::regular:
      break;
    case fs::file_type::directory:
      throw Error(who + ": is a directory, not a file");
    case fs::file_type::character:
    case fs::file_type::block:
      throw Error(who + ": is a device, not a regular file");
    case fs::file_type::fifo:
      throw Error(who + ": is a FIFO (named pipe), not a regular file");
    case fs::file_type::socket:
      throw Error(who + ": is a socket, not a regular file");
    default:
      throw Error(who + ": is not a regular file");
  }
  const std::uintmax_t size = fs::file_size(path, error);
  const std::string limit = "larger than the limit of " + bytesText(maxBytes);
  if (!error && size > maxBytes) throw Error(who + ": is " + bytesText(size) + ", " + limit);

  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(who + ": cannot be read");
  std::string text;
  text.reserve(error ? 0 : static_cast<std::size_t>(size));
  char buffer[1 << 16];
  while (file) {
    file.read(buffer, sizeof buffer);
    text.append(buffer, static_cast<std::size_t>(file.gcount()));
    if (text.size() > maxBytes) throw Error(who + ": is " + limit);
  }
  if (file.bad()) throw Error(who + ": cannot be read: read error");
  return text;
}

}  // namespace collide::scene
