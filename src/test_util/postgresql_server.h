// A throwaway PostgreSQL server for the archive's tests: initdb in a fresh temporary directory,
// started on a free port of 127.0.0.1 (and a socket in that directory), stopped and removed when
// the test program ends. As root (CI), the server runs as the unprivileged `postgres` user
// through runuser, since PostgreSQL refuses to run as root. Never the distribution's own cluster.
#pragma once

#include <string>

namespace inertest::testing {

class PostgresqlServer {
 public:
  // The one server of this test program, started on first use; stopped at exit.
  static PostgresqlServer& instance();

  // Whether the server runs; when not, why (why_unavailable).
  bool available() const { return available_; }
  const std::string& why_unavailable() const { return why_unavailable_; }

  // A new, empty database on the server; returns its postgresql:// URL.
  std::string create_database();

  void stop();
  ~PostgresqlServer();

 private:
  PostgresqlServer();
  bool available_ = false;
  std::string why_unavailable_;
  std::string bin_;
  std::string directory_;
  std::string as_user_;  // "runuser -u postgres -- " as root, else ""
  int port_ = 0;
  int databases_ = 0;
};

}  // namespace inertest::testing
