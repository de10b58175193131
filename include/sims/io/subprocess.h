// Child processes with pipes (POSIX): ffmpeg reads raw frames on its stdin, tar unpacks the
// viewer's three.js, tests drive Chromium over --remote-debugging-pipe (fds 3 and 4). No shell
// is involved, so paths with spaces or quotes need no escaping.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sims::io {

/// How the child's file descriptors are connected.
struct SubprocessOptions {
  bool pipe_stdin = false;             ///< Parent writes the child's stdin (WriteAll).
  bool pipe_stdout = false;            ///< Parent reads the child's stdout (ReadSome).
  std::filesystem::path stdout_file;   ///< Redirect stdout here (when not piped; "" = inherit).
  std::filesystem::path stderr_file;   ///< Redirect stderr here ("" = inherit).
  bool stderr_to_stdout = false;       ///< Send stderr wherever stdout goes (wins over file).
  std::vector<int> parent_writes_fds;  ///< Extra child fds (≥ 3) the child reads, parent writes.
  std::vector<int> parent_reads_fds;   ///< Extra child fds (≥ 3) the child writes, parent reads.
  std::vector<std::string> env;  ///< "NAME=VALUE" set (or replaced) in the child's environment.
};

/// A running child process. The destructor closes the pipes, kills the child if it is still
/// running and reaps it.
class Subprocess {
 public:
  /// Starts argv[0] (looked up in PATH); throws sims::Error naming the program when it
  /// cannot be started (e.g. "ffmpeg: not found; install it with the setup script").
  Subprocess(const std::vector<std::string>& argv, const SubprocessOptions& options = {});
  ~Subprocess();
  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  /// Process id.
  pid_t pid() const { return pid_; }
  /// Parent end of the pipe connected to child fd `child_fd` (0 = stdin, 1 = stdout, or an
  /// extra fd); −1 when not piped or already closed.
  int parent_fd(int child_fd) const;
  /// Writes everything to child fd `child_fd` (default stdin); false when the child closed it.
  bool WriteAll(const void* data, std::size_t size, int child_fd = 0);
  /// Reads up to `size` bytes from child fd `child_fd` (default stdout), waiting at most
  /// `timeout_ms` (−1 = forever); returns bytes read, 0 at end of file, −1 on timeout.
  long ReadSome(void* data, std::size_t size, int child_fd = 1, int timeout_ms = -1);
  /// Closes the parent end of a pipe (closing stdin tells ffmpeg the input ended).
  void ClosePipe(int child_fd);
  /// Waits for exit; returns the exit code (128 + signal when killed).
  int Wait();
  /// Waits at most `timeout_ms`; true (and `*code` set) if the child exited.
  bool WaitFor(int timeout_ms, int* code);
  /// Sends SIGKILL (if running) and reaps.
  void Kill();
  /// True until the child has been reaped.
  bool running() const { return pid_ > 0 && !reaped_; }

 private:
  struct Pipe {
    int child_fd;
    int parent_fd;
  };
  pid_t pid_ = -1;
  bool reaped_ = false;
  int exit_code_ = -1;
  std::vector<Pipe> pipes_;
  std::string program_;
};

/// True when `program` is found in PATH (or is an existing executable path).
bool ProgramAvailable(const std::string& program);

/// Runs a command to completion; returns its exit code and, if `output` is set, its stdout and
/// stderr together. Throws sims::Error when the program cannot be started.
int RunCommand(const std::vector<std::string>& argv, std::string* output = nullptr);

}  // namespace sims::io
