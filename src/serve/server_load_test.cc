// inertest serve under a bounded load (issue 17): two batches of 10 000 requests over 8 keep-alive
// connections on loopback (one under AddressSanitizer). It passes on no error and the process's
// memory flat between the batches (resident size after the second within a few MiB of after the
// first); throughput and p99 latency are printed, never asserted (they depend on the machine).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/archive/archive.h"
#include "inertest/serve/server.h"
#include "test_util/scale_factor_campaign.h"
#include "test_util/test_util.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INERTEST_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define INERTEST_UNDER_ASAN 1
#endif

namespace inertest::serve {
namespace {

constexpr int kConnections = 8;
constexpr int kRequestsPerBatch = 10000;
// The second batch is there to compare the resident size with the first's. Under AddressSanitizer
// freed memory waits in its quarantine and the size says nothing, so one batch is run there.
#ifdef INERTEST_UNDER_ASAN
constexpr int kBatches = 1;
#else
constexpr int kBatches = 2;
#endif
// The resident size may grow this much from the first batch's end to the second's.
constexpr double kFlatBytes = 4.0 * 1024 * 1024;

// The process's resident set size, bytes (/proc/self/statm).
double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0;
  double pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

// One keep-alive HTTP/1.1 connection; it reconnects when the server closes it (cpp-httplib ends a
// connection after a few requests).
class Connection {
 public:
  explicit Connection(int port) : port_(port) {}
  ~Connection() { close(); }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // GETs target; the status (0 when the exchange failed) and the body.
  std::pair<int, std::string> get(const std::string& target) {
    if (fd_ < 0 && !open()) return {0, ""};
    const std::string request = "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: keep-alive\r\n\r\n";
    if (::send(fd_, request.data(), request.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(request.size())) {
      close();
      return {0, ""};
    }
    std::string text;
    std::size_t header_end = std::string::npos;
    std::size_t length = 0;
    char buffer[65536];
    while (header_end == std::string::npos || text.size() < header_end + 4 + length) {
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) {
        close();
        return {0, ""};
      }
      text.append(buffer, static_cast<std::size_t>(n));
      if (header_end == std::string::npos && (header_end = text.find("\r\n\r\n")) != std::string::npos) {
        const auto at = text.find("Content-Length: ");
        length = at < header_end ? std::stoul(text.substr(at + 16)) : 0;
      }
    }
    const int status = text.rfind("HTTP/1.1 ", 0) == 0 ? std::stoi(text.substr(9, 3)) : 0;
    if (text.find("Connection: close") < header_end) close();
    return {status, text.substr(header_end + 4, length)};
  }

 private:
  bool open() {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port_));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0) return true;
    close();
    return false;
  }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  int port_;
  int fd_ = -1;
};

struct Batch {
  int errors = 0;
  double seconds = 0.0;
  std::vector<double> latencies;  // seconds, sorted
  double quantile(double q) const {
    return latencies[static_cast<std::size_t>(q * static_cast<double>(latencies.size() - 1))];
  }
};

// kRequestsPerBatch requests over kConnections connections, the targets taken in turn; a request
// fails when it gets no answer, a status other than 200 or an empty body.
Batch run_batch(int port, const std::vector<std::string>& targets) {
  std::vector<std::vector<double>> latencies(kConnections);
  std::atomic<int> errors{0};
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> clients;
  for (int c = 0; c < kConnections; ++c) {
    clients.emplace_back([&, c] {
      Connection connection(port);
      for (int i = c; i < kRequestsPerBatch; i += kConnections) {
        const auto sent = std::chrono::steady_clock::now();
        const auto [status, body] = connection.get(targets[static_cast<std::size_t>(i) % targets.size()]);
        latencies[static_cast<std::size_t>(c)].push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count());
        if (status != 200 || body.empty()) ++errors;
      }
    });
  }
  for (auto& client : clients) client.join();
  Batch batch;
  batch.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  batch.errors = errors;
  for (const auto& l : latencies) batch.latencies.insert(batch.latencies.end(), l.begin(), l.end());
  std::sort(batch.latencies.begin(), batch.latencies.end());
  return batch;
}

TEST(ServeLoad, TenThousandRequestsOverEightConnectionsWithoutErrorAndWithFlatMemory) {
  testing::ScratchDirectory scratch;
  const std::string db = scratch.path() + "/archive.sqlite";
  {
    const auto store = archive::open_archive(db);
    for (int i = 0; i < 12; ++i) {
      for (const std::string day : {"2026-03-02", "2026-03-09", "2026-03-16"}) {
        const std::string instrument = fmt::format("FOG-{:02}", i);
        store->add(testing::scale_factor_campaign(instrument, day, 36000.0 + 0.1 * i + day[9] * 0.01), instrument);
      }
    }
  }
  ServerOptions options;
  options.db = db;
  options.port = 0;
  Server server(options);
  std::thread thread([&server] { server.run(); });
  const std::string campaign = [&] {
    Connection connection(server.port());
    return nlohmann::json::parse(connection.get("/api/campaigns").second)["campaigns"][0]["id"].get<std::string>();
  }();
  const std::vector<std::string> targets = {
      "/api/instruments", "/api/campaigns", "/api/campaigns/" + campaign,
      "/api/instruments/FOG-03/history?figure=scale_factor/scale_factor",
      "/api/fleet?figure=scale_factor/scale_factor", "/instruments/FOG-07"};

  std::vector<Batch> batches;
  std::vector<double> resident;
  for (int b = 0; b < kBatches; ++b) {
    batches.push_back(run_batch(server.port(), targets));
    resident.push_back(resident_bytes());
    const Batch& batch = batches.back();
    std::printf("serve load, batch %d: %d requests over %d connections in %.2f s: %.0f requests/s, "
                "latency p50 %.2f ms, p99 %.2f ms, max %.2f ms; %d errors; resident %.1f MiB\n",
                b + 1, kRequestsPerBatch, kConnections, batch.seconds, kRequestsPerBatch / batch.seconds,
                1e3 * batch.quantile(0.5), 1e3 * batch.quantile(0.99), 1e3 * batch.latencies.back(), batch.errors,
                resident.back() / (1024.0 * 1024.0));
  }
  server.stop();
  thread.join();

  for (const Batch& batch : batches) EXPECT_EQ(batch.errors, 0);
  if constexpr (kBatches == 2) {
    std::printf("serve load: resident size %+.2f MiB from the first batch's end to the second's\n",
                (resident[1] - resident[0]) / (1024.0 * 1024.0));
    EXPECT_LT(resident[1] - resident[0], kFlatBytes);
  }
}

}  // namespace
}  // namespace inertest::serve
