#pragma once
// Prometheus counters, gauges and histograms for the service, rendered in the text exposition format.
// Label values come only from fixed sets (route table, known methods or "other", status names, error codes),
// so cardinality and the size of /metrics stay bounded; they are escaped per the exposition format all the same.
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace lienewton::service {

class Histogram {
 public:
  explicit Histogram(std::vector<double> bounds) : bounds_(std::move(bounds)), counts_(bounds_.size() + 1, 0) {}
  void observe(double value);
  // Appends the _bucket/_sum/_count lines; labels is "" or `key="value"`.
  void render(std::string& out, const std::string& name, const std::string& labels) const;

 private:
  std::vector<double> bounds_;
  std::vector<std::uint64_t> counts_;  // per bucket (not cumulative); last one is +Inf
  double sum_ = 0;
  std::uint64_t count_ = 0;
};

class Metrics {
 public:
  Metrics();
  void request_finished(const std::string& route, const std::string& method, int status, double seconds);
  void solve_finished(const std::string& status, int iterations);
  void rejected(const std::string& reason);
  // How an NDJSON/SSE stream ended: "result" or the error code of its terminal error record.
  void stream_ended(const std::string& outcome);
  void stream_started() { ++streams_in_flight_; }
  void stream_finished() { --streams_in_flight_; }
  void work_started() { ++work_in_flight_; }
  void work_finished() { --work_in_flight_; }
  long streams_in_flight() const { return streams_in_flight_.load(); }
  long work_in_flight() const { return work_in_flight_.load(); }
  std::uint64_t solves(const std::string& status) const;
  std::string render() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::tuple<std::string, std::string, int>, std::uint64_t> requests_;
  std::map<std::string, Histogram> latency_;  // per route
  std::map<std::string, std::uint64_t> solves_;
  std::map<std::string, std::uint64_t> rejected_;
  std::map<std::string, std::uint64_t> stream_outcomes_;
  Histogram iterations_;
  std::atomic<long> streams_in_flight_{0};
  std::atomic<long> work_in_flight_{0};
};

}  // namespace lienewton::service
