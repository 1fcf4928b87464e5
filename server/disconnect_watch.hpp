#pragma once
// Notices a client that closed its connection while its request runs, for answers that write nothing until the
// work ends (plain JSON and pictures): cpp-httplib 0.11.4 only tells a handler so when a write fails. One thread
// polls the sockets of the running requests every kPeriod; a peer's FIN or RST (nginx closes its upstream
// connection when its own client leaves) sets the request's flag, which its cancellation token reads.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace lienewton::service {

class DisconnectWatch {
 public:
  static constexpr std::chrono::milliseconds kPeriod{50};
  DisconnectWatch();
  ~DisconnectWatch();
  DisconnectWatch(const DisconnectWatch&) = delete;
  DisconnectWatch& operator=(const DisconnectWatch&) = delete;

  // A flag set once the peer of `socket` has closed; watched until the last copy of the pointer is dropped
  // (before the connection's socket is closed). socket < 0: a flag never set.
  std::shared_ptr<const std::atomic<bool>> watch(int socket);

 private:
  struct Entry {
    int socket;
    std::atomic<bool>* gone;
  };
  void run();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Entry> entries_;
  bool stopping_ = false;
  std::thread thread_;
};

// The descriptor of this process's TCP connection from remote_addr:remote_port to local_port (the address as
// cpp-httplib writes it, numeric), or -1: cpp-httplib 0.11.4 does not hand handlers their socket.
int connection_socket(const std::string& remote_addr, int remote_port, int local_port);

}  // namespace lienewton::service
