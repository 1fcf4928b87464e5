// Load client for scripts/load_test.sh: C keep-alive connections POST the same solve request R times in
// total and report throughput, p50/p99 latency, errors, and the solver's own time (the result's "seconds")
// so that the HTTP overhead can be read off.
#include <httplib.h>
#undef _res

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: load_test HOST PORT CONNECTIONS REQUESTS LABEL REQUEST_JSON\n");
    return 2;
  }
  const std::string host = argv[1];
  const int port = std::atoi(argv[2]);
  const int connections = std::max(1, std::atoi(argv[3]));
  const int requests = std::max(1, std::atoi(argv[4]));
  const std::string label = argv[5];
  const std::string body = argv[6];
  std::atomic<int> next{0};
  std::atomic<int> errors{0};
  std::vector<std::vector<double>> latency(static_cast<std::size_t>(connections));
  std::vector<std::vector<double>> solver(static_cast<std::size_t>(connections));
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int c = 0; c < connections; ++c) {
    threads.emplace_back([&, c] {
      httplib::Client client(host, port);
      client.set_keep_alive(true);
      client.set_tcp_nodelay(true);  // headers and body go out in two writes: avoid Nagle + delayed ACK
      client.set_read_timeout(30, 0);
      while (next.fetch_add(1) < requests) {
        const auto t0 = std::chrono::steady_clock::now();
        auto res = client.Post("/api/v1/solve", body, "application/json");
        const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!res || res->status != 200) {
          ++errors;
          continue;
        }
        latency[static_cast<std::size_t>(c)].push_back(dt);
        const auto j = nlohmann::json::parse(res->body, nullptr, false);
        if (j.is_discarded() || j.value("status", "") != "converged") {
          ++errors;
          continue;
        }
        solver[static_cast<std::size_t>(c)].push_back(j["seconds"].get<double>());
      }
    });
  }
  for (auto& t : threads) t.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<double> all, solve;
  for (auto& v : latency) all.insert(all.end(), v.begin(), v.end());
  for (auto& v : solver) solve.insert(solve.end(), v.begin(), v.end());
  std::sort(all.begin(), all.end());
  std::sort(solve.begin(), solve.end());
  auto pct = [](const std::vector<double>& v, double p) {
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
  };
  std::printf("%-6s requests=%d connections=%d errors=%d throughput=%.0f req/s p50=%.3f ms p99=%.3f ms "
              "solver_p50=%.3f ms overhead_p50=%.3f ms\n",
              label.c_str(), requests, connections, errors.load(), static_cast<double>(all.size()) / wall,
              pct(all, 0.5) * 1e3, pct(all, 0.99) * 1e3, pct(solve, 0.5) * 1e3, (pct(all, 0.5) - pct(solve, 0.5)) * 1e3);
  return errors.load() == 0 ? 0 : 1;
}
