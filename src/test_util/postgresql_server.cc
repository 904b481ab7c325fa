#include "test_util/postgresql_server.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <pwd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <fmt/format.h>

namespace inertest::testing {
namespace {

// A port nobody listens on now: bind port 0, read what the kernel chose, release it.
int free_port() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof address;
  int port = 0;
  if (::bind(s, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
      ::getsockname(s, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    port = ntohs(address.sin_port);
  }
  ::close(s);
  return port;
}

// The server once a test has asked for it; null in a test program that never did.
std::unique_ptr<PostgresqlServer>& started_server() {
  static std::unique_ptr<PostgresqlServer> server;
  return server;
}

// Stops the server, if one was started, when the test program ends (after every test, before
// static destruction). It must not start one: every test process would pay an initdb.
class StopServer : public ::testing::Environment {
 public:
  void TearDown() override {
    if (started_server()) started_server()->stop();
  }
};
[[maybe_unused]] ::testing::Environment* const stop_server = ::testing::AddGlobalTestEnvironment(new StopServer);

}  // namespace

PostgresqlServer& PostgresqlServer::instance() {
  std::unique_ptr<PostgresqlServer>& server = started_server();
  if (!server) server.reset(new PostgresqlServer);
  return *server;
}

PostgresqlServer::PostgresqlServer() {
  for (const char* version : {"15", "16", "17", "14", "13"}) {
    const std::string bin = fmt::format("/usr/lib/postgresql/{}/bin", version);
    if (std::filesystem::exists(bin + "/initdb") && std::filesystem::exists(bin + "/pg_ctl")) {
      bin_ = bin;
      break;
    }
  }
  if (bin_.empty()) {
    why_unavailable_ = "PostgreSQL server binaries (initdb, pg_ctl under /usr/lib/postgresql/*/bin) are not installed: "
                   "run scripts/install-deps.sh";
    return;
  }
  char pattern[] = "/tmp/inertest-pg-XXXXXX";
  if (::mkdtemp(pattern) == nullptr) {
    why_unavailable_ = "cannot create a temporary directory for the PostgreSQL server";
    return;
  }
  directory_ = pattern;
  if (::geteuid() == 0) {
    const passwd* user = ::getpwnam("postgres");
    if (user == nullptr || ::chown(directory_.c_str(), user->pw_uid, user->pw_gid) != 0) {
      why_unavailable_ = "running as root without a `postgres` user to run the PostgreSQL server as";
      return;
    }
    as_user_ = "runuser -u postgres -- ";
  }
  port_ = free_port();
  const std::string data = directory_ + "/data";
  const std::string init = fmt::format("{}{}/initdb -D {} -A trust -U inertest --no-sync > {}/initdb.log 2>&1",
                                       as_user_, bin_, data, directory_);
  const std::string start = fmt::format(
      "{}{}/pg_ctl -D {} -l {}/server.log -w -t 60 -o \"-p {} -k {} -c listen_addresses=127.0.0.1 -c fsync=off\" "
      "start > /dev/null 2>&1",
      as_user_, bin_, data, directory_, port_, directory_);
  if (std::system(init.c_str()) != 0 || std::system(start.c_str()) != 0) {
    why_unavailable_ = "the PostgreSQL server did not start; see the logs in " + directory_;
    directory_.clear();  // keep the logs for whoever reads the message
    ADD_FAILURE() << why_unavailable_;
    return;
  }
  available_ = true;
}

std::string PostgresqlServer::create_database() {
  const std::string name = fmt::format("archive_test_{}", ++databases_);
  const std::string command =
      fmt::format("{}/createdb -h 127.0.0.1 -p {} -U inertest {} > /dev/null 2>&1", bin_, port_, name);
  if (std::system(command.c_str()) != 0) ADD_FAILURE() << "createdb failed: " << command;
  return fmt::format("postgresql://inertest@127.0.0.1:{}/{}", port_, name);
}

void PostgresqlServer::stop() {
  if (available_) {
    const std::string command =
        fmt::format("{}{}/pg_ctl -D {}/data -m fast -w stop > /dev/null 2>&1", as_user_, bin_, directory_);
    [[maybe_unused]] const int status = std::system(command.c_str());
    available_ = false;
    why_unavailable_ = "the PostgreSQL server was stopped";
  }
  if (!directory_.empty()) {
    std::error_code ignored;
    std::filesystem::remove_all(directory_, ignored);
    directory_.clear();
  }
}

PostgresqlServer::~PostgresqlServer() { stop(); }

}  // namespace inertest::testing
