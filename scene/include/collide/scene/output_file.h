// The files `collide run` writes (the recording, the events, the summary), written so that nothing
// the user owns is lost: every path is checked before the run, every write and the close are
// checked, and a file is replaced only once it is complete (docs/reliability.md, "Bad input").
#pragma once

#include <collide/scene/scene.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace collide::scene {

// One output of a run: what it is ("recording", "events", "summary"; messages say "WHAT file PATH")
// and where it goes. An empty path is no output.
struct OutputPath {
  std::string what;
  std::filesystem::path path;
};

// Throws collide::Error, before anything is written, when an output path is a directory, lies in a
// folder that does not exist, is the scene's own file or one of its OBJ files (scene.file,
// scene.objFiles), or is the path of another output. Paths are compared once normalised and with
// symbolic links followed (std::filesystem::weakly_canonical), and existing files also by identity,
// so a hard link or a "./" does not slip past. A device (/dev/null) may take more than one output.
void checkOutputPaths(const Scene& scene, const std::vector<OutputPath>& outputs,
                      const std::vector<OutputPath>& otherInputs = {});

// A file written through a temporary file beside it (".NAME.tmp-PID-N", with the target's
// permissions when it exists) that replaces the target only on commit(); until then the target is
// untouched, and an OutputFile destroyed uncommitted removes its temporary file. A target that
// exists and is not a regular file (a device such as /dev/null, a FIFO) is written directly. A
// symbolic link is followed: the file it leads to is replaced, the link kept. Every write, the
// flush and the close are checked: a failure throws collide::Error("WHAT file PATH: cannot be
// written: REASON").
class OutputFile {
 public:
  OutputFile(std::filesystem::path path, std::string what);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(std::string_view text);
  // Writes what is buffered and closes the file (the temporary one, until commit). Throws when
  // either fails; commit() does it if it was not done.
  void close();
  // close(), then renames the temporary file onto the target.
  void commit();

 private:
  [[noreturn]] void fail(const std::string& reason);
  void flush();

  std::filesystem::path path_;       // the target, as given
  std::filesystem::path temporary_;  // empty when writing the target directly
  std::filesystem::path real_;       // what commit() replaces: the target with its links followed
  std::string what_;
  std::string buffer_;
  int fd_ = -1;
  bool committed_ = false;
};

}  // namespace collide::scene
