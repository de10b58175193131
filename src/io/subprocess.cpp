#include "sims/io/subprocess.h"

#include "sims/core/environment.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "sims/core/error.h"

namespace sims::io {

namespace {

// Child side after fork: only async-signal-safe calls until exec.
[[noreturn]] void ChildExec(char* const* argv, char* const* envp, const int* src, const int* dst,
                            int n, int stdout_file, int stderr_file, int report_fd) {
  // Move every source above the highest target first so dup2 never clobbers a source.
  int moved[16];
  for (int i = 0; i < n; ++i) moved[i] = fcntl(src[i], F_DUPFD, 64);
  for (int i = 0; i < n; ++i) dup2(moved[i], dst[i]);
  for (int i = 0; i < n; ++i) close(moved[i]);
  if (stdout_file >= 0) dup2(stdout_file, 1);
  if (stderr_file >= 0) dup2(stderr_file, 2);
  if (stderr_file == -2) dup2(1, 2);
  execvpe(argv[0], argv, envp);
  const int err = errno;
  (void)!write(report_fd, &err, sizeof(err));
  _exit(127);
}

int OpenForWrite(const std::filesystem::path& p) {
  if (p.empty()) return -1;
  const int fd = open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) ThrowInputError(p.string(), "", "a writable location", std::strerror(errno));
  return fd;
}

// Blocks SIGPIPE for this thread so a write to a closed pipe returns EPIPE instead of
// killing the process, and swallows the pending signal before unblocking.
class ScopedNoSigpipe {
 public:
  ScopedNoSigpipe() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &set_, &old_);
  }
  ~ScopedNoSigpipe() {
    if (got_epipe_) {
      timespec zero{0, 0};
      while (sigtimedwait(&set_, nullptr, &zero) > 0) {
      }
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  void SawEpipe() { got_epipe_ = true; }

 private:
  sigset_t set_, old_;
  bool got_epipe_ = false;
};

}  // namespace

Subprocess::Subprocess(const std::vector<std::string>& argv, const SubprocessOptions& options) {
  SIMS_CHECK(!argv.empty());
  program_ = argv[0];
  std::vector<int> src, dst;
  std::vector<int> child_ends;
  auto add_pipe = [&](int child_fd, bool parent_writes) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) SIMS_CHECK_MSG(false, "pipe2 failed");
    const int child_end = parent_writes ? fds[0] : fds[1];
    const int parent_end = parent_writes ? fds[1] : fds[0];
    src.push_back(child_end);
    dst.push_back(child_fd);
    child_ends.push_back(child_end);
    pipes_.push_back({child_fd, parent_end});
  };
  if (options.pipe_stdin) add_pipe(0, true);
  if (options.pipe_stdout) add_pipe(1, false);
  for (int fd : options.parent_writes_fds) add_pipe(fd, true);
  for (int fd : options.parent_reads_fds) add_pipe(fd, false);
  SIMS_CHECK(src.size() <= 16);
  const int out_fd = options.pipe_stdout ? -1 : OpenForWrite(options.stdout_file);
  int err_fd = -1;
  try {
    err_fd = options.stderr_to_stdout ? -1 : OpenForWrite(options.stderr_file);
  } catch (...) {
    if (out_fd >= 0) close(out_fd);
    throw;
  }
  int report[2];
  if (pipe2(report, O_CLOEXEC) != 0) SIMS_CHECK_MSG(false, "pipe2 failed");

  std::vector<std::string> args = argv;
  std::vector<char*> cargv;
  for (auto& a : args) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  // The child's environment is built before fork: nothing after it may allocate.
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e;
    const auto name = entry.substr(0, entry.find('=') + 1);
    bool replaced = false;
    for (const auto& x : options.env) replaced |= x.compare(0, name.size(), name) == 0;
    if (!replaced) env.push_back(entry);
  }
  env.insert(env.end(), options.env.begin(), options.env.end());
  std::vector<char*> cenv;
  for (auto& e : env) cenv.push_back(e.data());
  cenv.push_back(nullptr);

  pid_ = fork();
  if (pid_ == 0)
    ChildExec(cargv.data(), cenv.data(), src.data(), dst.data(), static_cast<int>(src.size()),
              out_fd, options.stderr_to_stdout ? -2 : err_fd, report[1]);
  for (int fd : child_ends) close(fd);
  if (out_fd >= 0) close(out_fd);
  if (err_fd >= 0) close(err_fd);
  close(report[1]);
  if (pid_ < 0) {
    close(report[0]);
    for (auto& p : pipes_) close(p.parent_fd);
    pipes_.clear();
    ThrowInputError(program_, "", "a program that can be started", "fork failed");
  }
  int child_errno = 0;
  long n;
  do {
    n = read(report[0], &child_errno, sizeof(child_errno));
  } while (n < 0 && errno == EINTR);
  close(report[0]);
  if (n == static_cast<long>(sizeof(child_errno))) {
    int status;
    waitpid(pid_, &status, 0);
    reaped_ = true;
    for (auto& p : pipes_) close(p.parent_fd);
    pipes_.clear();
    ThrowInputError(program_, "", "an installed program (run cmake/setup.sh)",
                    std::string("cannot start: ") + std::strerror(child_errno));
  }
}

Subprocess::~Subprocess() {
  for (auto& p : pipes_)
    if (p.parent_fd >= 0) close(p.parent_fd);
  pipes_.clear();
  if (running()) {
    int code;
    // Give a child whose stdin just closed a moment to finish on its own.
    if (!WaitFor(200, &code)) Kill();
  }
}

int Subprocess::parent_fd(int child_fd) const {
  for (const auto& p : pipes_)
    if (p.child_fd == child_fd) return p.parent_fd;
  return -1;
}

bool Subprocess::WriteAll(const void* data, std::size_t size, int child_fd) {
  const int fd = parent_fd(child_fd);
  SIMS_CHECK_MSG(fd >= 0, "no pipe to child fd " + std::to_string(child_fd));
  ScopedNoSigpipe guard;
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t w = write(fd, p, size);
    if (w < 0) {
      if (errno == EINTR) continue;
      if (errno == EPIPE) guard.SawEpipe();
      return false;
    }
    p += w;
    size -= static_cast<std::size_t>(w);
  }
  return true;
}

long Subprocess::ReadSome(void* data, std::size_t size, int child_fd, int timeout_ms) {
  const int fd = parent_fd(child_fd);
  SIMS_CHECK_MSG(fd >= 0, "no pipe from child fd " + std::to_string(child_fd));
  pollfd pfd{fd, POLLIN, 0};
  for (;;) {
    const int r = poll(&pfd, 1, timeout_ms);
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) return -1;
    break;
  }
  for (;;) {
    const ssize_t n = read(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    return n < 0 ? 0 : static_cast<long>(n);
  }
}

void Subprocess::ClosePipe(int child_fd) {
  for (auto& p : pipes_) {
    if (p.child_fd == child_fd && p.parent_fd >= 0) {
      close(p.parent_fd);
      p.parent_fd = -1;
    }
  }
}

int Subprocess::Wait() {
  if (!running()) return exit_code_;
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  reaped_ = true;
  exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return exit_code_;
}

bool Subprocess::WaitFor(int timeout_ms, int* code) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (running()) {
    int status = 0;
    const pid_t r = waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
      reaped_ = true;
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      break;
    }
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (code) *code = exit_code_;
  return true;
}

void Subprocess::Kill() {
  if (!running()) return;
  kill(pid_, SIGKILL);
  Wait();
}

bool ProgramAvailable(const std::string& program) {
  auto executable = [](const std::filesystem::path& p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(p.c_str(), X_OK) == 0;
  };
  if (program.find('/') != std::string::npos) return executable(program);
  // $PATH as read at start-up (core/environment.h), as exec would search it.
  std::string dirs = InstalledEnvironment().Variable("PATH");
  if (dirs.empty()) dirs = "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = dirs.find(':', start);
    const std::string dir =
        dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!dir.empty() && executable(std::filesystem::path(dir) / program)) return true;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return false;
}

int RunCommand(const std::vector<std::string>& argv, std::string* output) {
  SubprocessOptions opt;
  opt.pipe_stdout = output != nullptr;
  opt.stderr_to_stdout = output != nullptr;
  Subprocess p(argv, opt);
  if (output) {
    output->clear();
    char buf[65536];
    for (;;) {
      const long n = p.ReadSome(buf, sizeof(buf));
      if (n <= 0) break;
      output->append(buf, static_cast<std::size_t>(n));
    }
  }
  return p.Wait();
}

}  // namespace sims::io
