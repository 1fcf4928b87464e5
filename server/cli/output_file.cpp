#include "server/cli/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include "server/http_errors.hpp"

namespace lienewton::cli {
namespace {

using service::ApiError;

// The signals whose default action ends the process (SIGKILL and SIGSTOP cannot be caught).
constexpr std::array kEndingSignals{SIGHUP,  SIGINT,  SIGQUIT, SIGILL,  SIGABRT, SIGBUS,    SIGFPE,  SIGUSR1,
                                    SIGSEGV, SIGUSR2, SIGPIPE, SIGALRM, SIGTERM, SIGXCPU,  SIGXFSZ, SIGVTALRM,
                                    SIGPROF, SIGSYS,  SIGTRAP};

// The temporary's name for the handler: a fixed buffer, read with async-signal-safe calls only.
char temporary[PATH_MAX + 32];

extern "C" void remove_temporary_and_die(int signal) {
  if (temporary[0] != '\0') unlink(temporary);
  std::signal(signal, SIG_DFL);
  raise(signal);
}

// Installs the handler for the life of one write; restores what was there before.
class TemporaryGuard {
 public:
  explicit TemporaryGuard(const std::string& path) {
    std::memcpy(temporary, path.c_str(), path.size() + 1);
    struct sigaction action {};
    action.sa_handler = remove_temporary_and_die;
    sigfillset(&action.sa_mask);
    for (std::size_t i = 0; i < kEndingSignals.size(); ++i) sigaction(kEndingSignals[i], &action, &previous_[i]);
  }
  ~TemporaryGuard() {
    for (std::size_t i = 0; i < kEndingSignals.size(); ++i) sigaction(kEndingSignals[i], &previous_[i], nullptr);
    temporary[0] = '\0';
  }
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;

 private:
  std::array<struct sigaction, kEndingSignals.size()> previous_{};
};

[[noreturn]] void cannot_write(const std::string& path, int error) {
  throw ApiError(500, "output_failed", "out", "cannot write " + path + ": " + std::strerror(error));
}

bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// Where the answer goes: path, or the file a symbolic link names (through), and the mode an existing file has.
struct Target {
  std::string path;
  bool exists = false;
  bool fifo = false;
  mode_t mode = 0;
};

Target target_of(const std::string& path, bool through) {
  Target t{path};
  struct stat link {};
  if (lstat(path.c_str(), &link) != 0) {
    if (errno != ENOENT) cannot_write(path, errno);
    return t;
  }
  if (S_ISLNK(link.st_mode)) {
    if (!through)
      throw ApiError(400, "usage", "out", path + " is a symbolic link: give --out-through to write the file it names");
    char* resolved = realpath(path.c_str(), nullptr);
    if (!resolved) {
      if (errno != ENOENT) cannot_write(path, errno);
      throw ApiError(400, "usage", "out", path + " is a symbolic link to nothing: give the file's own name");
    }
    t.path = resolved;
    std::free(resolved);
    return target_of(t.path, through);
  }
  t.exists = true;
  t.mode = link.st_mode & 07777;
  if (S_ISFIFO(link.st_mode)) {
    if (!through) throw ApiError(400, "usage", "out", path + " is a FIFO: give --out-through to write into it");
    t.fifo = true;
    return t;
  }
  if (!S_ISREG(link.st_mode)) throw ApiError(400, "usage", "out", path + " is not a regular file");
  return t;
}

}  // namespace

void write_output_file(const std::string& path, const std::string& bytes, bool through) {
  const Target target = target_of(path, through);
  if (target.fifo) {  // a reader waits on it: the bytes go in as they are, there is nothing to rename
    const int fd = open(target.path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) cannot_write(path, errno);
    const bool written = write_all(fd, bytes);
    const int error = errno;
    close(fd);
    if (!written) cannot_write(path, error);
    return;
  }
  const std::string part = target.path + ".part-" + std::to_string(getpid());
  if (part.size() >= sizeof temporary) throw ApiError(400, "usage", "out", "the name " + path + " is too long");
  const TemporaryGuard guard(part);
  // A new file's mode is what open gives under the umask; an existing file's is kept exactly.
  const int fd = open(part.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, target.exists ? 0600 : 0666);
  if (fd < 0) cannot_write(path, errno);
  bool ok = write_all(fd, bytes);
  int error = errno;
  if (ok && target.exists && fchmod(fd, target.mode) != 0) ok = false, error = errno;
  if (close(fd) != 0 && ok) ok = false, error = errno;
  if (ok && rename(part.c_str(), target.path.c_str()) != 0) ok = false, error = errno;
  if (!ok) {
    unlink(part.c_str());
    cannot_write(path, error);
  }
}

}  // namespace lienewton::cli
