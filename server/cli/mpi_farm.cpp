#include "server/cli/mpi_farm.hpp"

#include <mpi.h>

#include <chrono>
#include <cstring>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace lienewton::cli {
namespace {

constexpr int kItemTag = 1;    // rank 0 -> worker: an item index, or kRoundOver
constexpr int kResultTag = 2;  // worker -> rank 0: the item index, then the item's bytes
constexpr int kRoundOver = -1;
constexpr int kItemsInFlight = 2;  // per worker: it computes one while the next is on its way

void check(int code, const char* call) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI call failed: ") + call);
}

// Waits for a message without spinning: Open MPI's blocking receive polls at full speed and would take the core
// that rank 0's computing thread (or an oversubscribed rank) needs. 50 us is far below an item's cost.
MPI_Status wait_for(int source, int tag) {
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (arrived) return status;
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
}

// The next item of order to compute, shared by rank 0's computing thread and its dispatcher.
class ItemQueue {
 public:
  explicit ItemQueue(const std::vector<int>& order) : order_(order) {}
  int claim() {
    std::lock_guard lock(mutex_);
    return stopped_ || next_ >= order_.size() ? kRoundOver : order_[next_++];
  }
  void stop() {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }

 private:
  const std::vector<int>& order_;
  std::size_t next_ = 0;
  bool stopped_ = false;
  std::mutex mutex_;
};

}  // namespace

bool MpiSession::launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  // Only the main thread calls MPI; rank 0's computing thread does not.
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED) throw std::runtime_error("the MPI library does not support MPI_THREAD_FUNNELED");
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
}

MpiSession::~MpiSession() { MPI_Finalize(); }

std::string MpiSession::broadcast(std::string text) const {
  unsigned long long size = text.size();
  check(MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  text.resize(size);
  check(MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return text;
}

bool MpiFarm::run(const std::vector<int>& order, const std::function<std::string(int)>& compute,
                  const std::function<bool(int, const std::string&)>& deliver) const {
  if (session_.rank() == 0) return hand_out(order, compute, deliver);
  work(compute);
  return false;
}

bool MpiFarm::hand_out(const std::vector<int>& order, const std::function<std::string(int)>& compute,
                       const std::function<bool(int, const std::string&)>& deliver) const {
  ItemQueue queue(order);
  std::mutex deliver_mutex;
  std::exception_ptr failure;
  // Delivers one result; a false answer or an exception stops handing out items (the round still ends cleanly).
  const auto file = [&](int item, const std::string& bytes) {
    std::lock_guard lock(deliver_mutex);
    try {
      if (!failure && deliver(item, bytes)) return;
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
    queue.stop();
  };
  const auto send_item = [](int item, int rank) {
    check(MPI_Send(&item, 1, MPI_INT, rank, kItemTag, MPI_COMM_WORLD), "MPI_Send");
  };
  int in_flight = 0;
  for (int rank = 1; rank < session_.size(); ++rank)
    for (int k = 0; k < kItemsInFlight; ++k)
      if (const int item = queue.claim(); item != kRoundOver) {
        send_item(item, rank);
        ++in_flight;
      }
  std::thread local([&] {
    for (int item; (item = queue.claim()) != kRoundOver;) {
      std::string bytes;
      try {
        bytes = compute(item);
      } catch (...) {
        std::lock_guard lock(deliver_mutex);
        if (!failure) failure = std::current_exception();
        queue.stop();
        return;
      }
      file(item, bytes);
    }
  });
  std::string bytes;
  while (in_flight > 0) {
    const MPI_Status status = wait_for(MPI_ANY_SOURCE, kResultTag);
    int count = 0;
    check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
    bytes.resize(static_cast<std::size_t>(count));
    check(MPI_Recv(bytes.data(), count, MPI_CHAR, status.MPI_SOURCE, kResultTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv");
    --in_flight;
    int item = 0;
    std::memcpy(&item, bytes.data(), sizeof item);
    file(item, bytes.substr(sizeof item));
    if (const int next = queue.claim(); next != kRoundOver) {
      send_item(next, status.MPI_SOURCE);
      ++in_flight;
    }
  }
  local.join();
  for (int rank = 1; rank < session_.size(); ++rank) send_item(kRoundOver, rank);
  if (failure) std::rethrow_exception(failure);
  return true;
}

void MpiFarm::work(const std::function<std::string(int)>& compute) const {
  for (;;) {
    wait_for(0, kItemTag);
    int item = 0;
    check(MPI_Recv(&item, 1, MPI_INT, 0, kItemTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
    if (item == kRoundOver) return;
    std::string message(sizeof item, '\0');
    std::memcpy(message.data(), &item, sizeof item);
    try {
      message += compute(item);
    } catch (const std::exception& e) {
      // Rank 0 would wait for this item for ever: end the whole job.
      std::cerr << "lienewton: rank " << session_.rank() << " failed on item " << item << ": " << e.what() << "\n";
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    check(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kResultTag, MPI_COMM_WORLD),
          "MPI_Send");
  }
}

}  // namespace lienewton::cli
