#include "server/disconnect_watch.hpp"

#include <dirent.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>

namespace lienewton::service {

DisconnectWatch::DisconnectWatch() : thread_([this] { run(); }) {}

DisconnectWatch::~DisconnectWatch() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::shared_ptr<const std::atomic<bool>> DisconnectWatch::watch(int socket) {
  if (socket < 0) return std::make_shared<std::atomic<bool>>(false);
  auto* gone = new std::atomic<bool>(false);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back({socket, gone});
  }
  wake_.notify_all();
  // The entry leaves the watch under the lock, so the thread never polls a socket after its request ended.
  return std::shared_ptr<const std::atomic<bool>>(gone, [this](const std::atomic<bool>* flag) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      entries_.erase(std::remove_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.gone == flag; }),
                     entries_.end());
    }
    delete flag;
  });
}

void DisconnectWatch::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  std::vector<pollfd> fds;
  while (!stopping_) {
    if (entries_.empty()) {
      wake_.wait(lock, [&] { return stopping_ || !entries_.empty(); });
      continue;
    }
    fds.clear();
    for (const Entry& e : entries_) fds.push_back({e.socket, POLLIN | POLLRDHUP, 0});
    // Timeout 0: the lock is held, so that no entry's socket is closed while it is polled.
    ::poll(fds.data(), fds.size(), 0);
    for (std::size_t i = 0; i < fds.size(); ++i) {
      const short ev = fds[i].revents;
      bool gone = (ev & (POLLRDHUP | POLLHUP | POLLERR)) != 0;
      if (!gone && (ev & POLLIN)) {
        // The request was read whole: a readable socket holds either a pipelined request or the peer's EOF.
        char byte;
        const ssize_t n = ::recv(fds[i].fd, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
        gone = n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
      }
      if (gone) entries_[i].gone->store(true);
    }
    wake_.wait_for(lock, kPeriod, [&] { return stopping_; });
  }
}

namespace {

// The numeric host and the port of a socket address, as cpp-httplib reads its peers'.
bool numeric(const sockaddr_storage& addr, socklen_t len, std::string& host, int& port) {
  char h[NI_MAXHOST], p[NI_MAXSERV];
  if (::getnameinfo(reinterpret_cast<const sockaddr*>(&addr), len, h, sizeof h, p, sizeof p,
                    NI_NUMERICHOST | NI_NUMERICSERV) != 0)
    return false;
  host = h;
  port = std::atoi(p);
  return true;
}

}  // namespace

int connection_socket(const std::string& remote_addr, int remote_port, int local_port) {
  DIR* dir = ::opendir("/proc/self/fd");
  if (!dir) return -1;
  int found = -1;
  while (const dirent* entry = ::readdir(dir)) {
    if (entry->d_name[0] == '.') continue;
    const int fd = std::atoi(entry->d_name);
    sockaddr_storage local{}, peer{};
    socklen_t local_len = sizeof local, peer_len = sizeof peer;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_len) != 0) continue;
    if (local.ss_family != AF_INET && local.ss_family != AF_INET6) continue;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_len) != 0) continue;
    std::string local_host, peer_host;
    int lport = 0, pport = 0;
    if (numeric(local, local_len, local_host, lport) && numeric(peer, peer_len, peer_host, pport) &&
        lport == local_port && pport == remote_port && peer_host == remote_addr) {
      found = fd;
      break;
    }
  }
  ::closedir(dir);
  return found;
}

}  // namespace lienewton::service
