#include "server/metrics.hpp"

#include <cmath>
#include <cstdio>
#include <tuple>

#include "core/status.hpp"

namespace lienewton::service {
namespace {

const std::vector<double> kLatencyBuckets{0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1,
                                          0.25,   0.5,   1,      2.5,   5,    10,   30,   60};
const std::vector<double> kIterationBuckets{1, 2, 3, 4, 5, 6, 8, 10, 15, 20, 30, 50, 100, 1000};

std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

// A label value per the text exposition format: backslash, double quote and line feed escaped.
std::string escape(const std::string& value) {
  std::string out;
  for (char c : value) {
    if (c == '\\') out += "\\\\";
    else if (c == '"') out += "\\\"";
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out;
}

std::string label_join(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  return a + "," + b;
}

}  // namespace

void Histogram::observe(double value) {
  if (!std::isfinite(value)) return;
  std::size_t i = 0;
  while (i < bounds_.size() && value > bounds_[i]) ++i;
  ++counts_[i];
  sum_ += value;
  ++count_;
}

void Histogram::render(std::string& out, const std::string& name, const std::string& labels) const {
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i <= bounds_.size(); ++i) {
    cumulative += counts_[i];
    const std::string le = i < bounds_.size() ? number(bounds_[i]) : "+Inf";
    out += name + "_bucket{" + label_join(labels, "le=\"" + le + "\"") + "} " + std::to_string(cumulative) + "\n";
  }
  const std::string braces = labels.empty() ? "" : "{" + labels + "}";
  out += name + "_sum" + braces + " " + number(sum_) + "\n";
  out += name + "_count" + braces + " " + std::to_string(count_) + "\n";
}

Metrics::Metrics() : iterations_(kIterationBuckets) {
  for (auto s : kAllStatuses) solves_[std::string(to_string(s))] = 0;  // every status visible from the start
}

void Metrics::request_finished(const std::string& route, const std::string& method, int status, double seconds) {
  std::lock_guard lock(mutex_);
  ++requests_[{route, method, status}];
  auto it = latency_.find(route);
  if (it == latency_.end()) it = latency_.emplace(route, Histogram(kLatencyBuckets)).first;
  it->second.observe(seconds);
}

void Metrics::solve_finished(const std::string& status, int iterations) {
  std::lock_guard lock(mutex_);
  ++solves_[status];
  iterations_.observe(iterations);
}

void Metrics::rejected(const std::string& reason) {
  std::lock_guard lock(mutex_);
  ++rejected_[reason];
}

void Metrics::stream_ended(const std::string& outcome) {
  std::lock_guard lock(mutex_);
  ++stream_outcomes_[outcome];
}

std::uint64_t Metrics::solves(const std::string& status) const {
  std::lock_guard lock(mutex_);
  auto it = solves_.find(status);
  return it == solves_.end() ? 0 : it->second;
}

std::string Metrics::render() const {
  std::lock_guard lock(mutex_);
  std::string out;
  out += "# HELP lienewton_http_requests_total HTTP requests by route, method and status code.\n";
  out += "# TYPE lienewton_http_requests_total counter\n";
  for (const auto& [key, count] : requests_) {
    const auto& [route, method, status] = key;
    out += "lienewton_http_requests_total{route=\"" + escape(route) + "\",method=\"" + escape(method) + "\",code=\"" +
           std::to_string(status) + "\"} " + std::to_string(count) + "\n";
  }
  out += "# HELP lienewton_http_request_duration_seconds Time from routing to the last byte, per route.\n";
  out += "# TYPE lienewton_http_request_duration_seconds histogram\n";
  for (const auto& [route, h] : latency_) {
    h.render(out, "lienewton_http_request_duration_seconds", "route=\"" + escape(route) + "\"");
  }
  out += "# HELP lienewton_solves_total Solves (single solves and sweep cells) by final status.\n";
  out += "# TYPE lienewton_solves_total counter\n";
  for (const auto& [status, count] : solves_) {
    out += "lienewton_solves_total{status=\"" + escape(status) + "\"} " + std::to_string(count) + "\n";
  }
  out += "# HELP lienewton_solve_iterations Iterations per solve.\n";
  out += "# TYPE lienewton_solve_iterations histogram\n";
  iterations_.render(out, "lienewton_solve_iterations", "");
  out += "# HELP lienewton_rejected_total Requests refused before any work, by reason.\n";
  out += "# TYPE lienewton_rejected_total counter\n";
  for (const auto& [reason, count] : rejected_) {
    out += "lienewton_rejected_total{reason=\"" + escape(reason) + "\"} " + std::to_string(count) + "\n";
  }
  out += "# HELP lienewton_streams_total Finished NDJSON/SSE streams by how they ended (result or error code).\n";
  out += "# TYPE lienewton_streams_total counter\n";
  for (const auto& [outcome, count] : stream_outcomes_) {
    out += "lienewton_streams_total{outcome=\"" + escape(outcome) + "\"} " + std::to_string(count) + "\n";
  }
  out += "# HELP lienewton_streams_in_flight Open NDJSON/SSE streams.\n";
  out += "# TYPE lienewton_streams_in_flight gauge\n";
  out += "lienewton_streams_in_flight " + std::to_string(streams_in_flight_.load()) + "\n";
  out += "# HELP lienewton_work_in_flight Requests holding a work slot (solves, sweeps, integrations, renders).\n";
  out += "# TYPE lienewton_work_in_flight gauge\n";
  out += "lienewton_work_in_flight " + std::to_string(work_in_flight_.load()) + "\n";
  return out;
}

}  // namespace lienewton::service
