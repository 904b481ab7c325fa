// `inertest serve` (issue 17): the results archive over HTTP. A JSON API under /api/ returns the
// very objects the CLI's --json prints (the same library functions make them):
//   GET /api/campaigns                                  archive list --json
//   GET /api/campaigns/{id}                             the campaign's results.json, as stored
//   GET /api/instruments                                archive instruments --json
//   GET /api/instruments/{id}/history?figure=P/F        archive history ID --figure P/F --json
//   GET /api/fleet?figure=P/F[&since=YYYY-MM-DD]        archive fleet --figure P/F --json
//   POST /api/campaigns (only with allow_add)           archive add --json, the body a results.json
//
// Contract: read-only unless allow_add; a POST must carry the server's token (header
// "Authorization: Bearer TOKEN") and a body of at most max_body_bytes. Ids, figure names and dates
// are checked against fixed patterns before they reach the archive (whose queries are all
// parameterised); a bad request gets a 4xx status with {"error": "..."} and the server keeps
// serving. Requests are served concurrently; the archive is used by one request at a time.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

namespace inertest::serve {

struct ServerOptions {
  std::string db;              // the archive: a file path (SQLite) or a postgresql:// URL
  std::string bind = "127.0.0.1";
  int port = 8080;             // 0: any free port (see Server::port)
  bool allow_add = false;      // accept POST /api/campaigns with the token
  std::size_t max_body_bytes = 16u << 20;
};

class Server {
 public:
  // Opens the archive (a SQLite file must exist) and binds the socket. Throws Error when either fails.
  explicit Server(const ServerOptions& options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // The port bound (the chosen one when options.port was 0).
  int port() const;
  // http://BIND:PORT/
  std::string url() const;
  // The token a POST must carry: 32 random hex digits, new for each server.
  const std::string& token() const;

  // Serves until stop() is called (from another thread or a signal handler's thread).
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace inertest::serve
