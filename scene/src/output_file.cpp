// Output files: paths checked before the run, written through a temporary file and renamed into
// place when complete, every write and the close checked.
#include <collide/error.h>
#include <collide/scene/output_file.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

namespace collide::scene {

namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& path) { return path.string(); }

fs::path folderOf(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// The path once normalised, links followed as far as it exists; the path itself if even that fails.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  fs::path real = fs::weakly_canonical(path, error);
  return error ? path.lexically_normal() : real;
}

bool samePath(const fs::path& a, const fs::path& b) {
  if (resolved(a) == resolved(b)) return true;
  std::error_code error;
  return fs::equivalent(a, b, error) && !error;  // hard links; false when either does not exist
}

}  // namespace

void checkOutputPaths(const Scene& scene, const std::vector<OutputPath>& outputs,
                      const std::vector<OutputPath>& otherInputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputPath& out = outputs[i];
    if (out.path.empty()) continue;
    const std::string who = out.what + " file " + quoted(out.path);
    std::error_code error;
    const fs::file_status status = fs::status(out.path, error);
    if (status.type() == fs::file_type::directory) throw Error(who + ": is a directory, not a file");
    const fs::path folder = folderOf(out.path);
    const fs::file_status folderStatus = fs::status(folder, error);
    if (folderStatus.type() == fs::file_type::not_found)
      throw Error(who + ": cannot be written: the folder " + quoted(folder) + " does not exist");
    if (folderStatus.type() != fs::file_type::directory)
      throw Error(who + ": cannot be written: " + quoted(folder) + " is not a folder");
    if (!scene.file.empty() && samePath(out.path, scene.file))
      throw Error(who + ": is the scene file being run; refusing to overwrite it");
    for (const fs::path& obj : scene.objFiles) {
      if (samePath(out.path, obj))
        throw Error(who + ": is the OBJ file " + quoted(obj) +
                    " that the scene reads; refusing to overwrite it");
    }
    for (const OutputPath& input : otherInputs) {
      if (!input.path.empty() && samePath(out.path, input.path))
        throw Error(who + ": is the " + input.what + " file the run reads; refusing to overwrite it");
    }
    if (status.type() == fs::file_type::character) continue;  // /dev/null takes any number of outputs
    for (std::size_t j = 0; j < i; ++j) {
      if (!outputs[j].path.empty() && samePath(out.path, outputs[j].path))
        throw Error(who + ": is also the " + outputs[j].what + " file; give each output its own path");
    }
  }
}

OutputFile::OutputFile(fs::path path, std::string what) : path_(std::move(path)), what_(std::move(what)) {
  std::error_code error;
  const fs::file_status status = fs::status(path_, error);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    // A device or a FIFO: there is nothing to replace, and a file renamed over /dev/null would
    // replace the device. Written directly.
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) fail(std::strerror(errno));
    return;
  }
  real_ = fs::is_symlink(fs::symlink_status(path_, error)) ? resolved(path_) : path_;
  const fs::path folder = folderOf(real_);
  // O_EXCL: a name nobody else holds (a left-over temporary file is skipped, never reused).
  static int counter = 0;
  for (int attempt = 0; fd_ < 0; ++attempt) {
    std::string name(".");
    name += real_.filename().string();
    name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    temporary_ = folder / name;
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);  // umask applies
    if (fd_ < 0 && (errno != EEXIST || attempt > 100)) {
      const int code = errno;
      temporary_.clear();
      fail(std::strerror(code));
    }
  }
  if (fs::is_regular_file(status)) ::fchmod(fd_, static_cast<mode_t>(status.permissions()));
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
}

void OutputFile::fail(const std::string& reason) {
  throw Error(what_ + " file " + quoted(path_) + ": cannot be written: " + reason);
}

void OutputFile::write(std::string_view text) {
  if (fd_ < 0) fail("already closed");
  buffer_.append(text);
  if (buffer_.size() >= (1u << 16)) flush();
}

void OutputFile::flush() {
  std::size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(n < 0 ? std::strerror(errno) : "nothing written");
    done += static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

void OutputFile::close() {
  if (fd_ < 0) return;
  flush();
  // A regular file reaches the disk before it replaces the target, so that a crash right after the
  // rename cannot leave an empty file where the old one was.
  if (!temporary_.empty() && ::fsync(fd_) != 0) fail(std::strerror(errno));
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(std::strerror(errno));
}

void OutputFile::commit() {
  close();
  if (committed_) return;
  if (!temporary_.empty() && std::rename(temporary_.c_str(), real_.c_str()) != 0) fail(std::strerror(errno));
  committed_ = true;
}

}  // namespace collide::scene
