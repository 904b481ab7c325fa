// inertest serve [--db DB] [--bind 127.0.0.1] [--port 8080] [--allow-add] [--max-body BYTES]
#include <fmt/format.h>
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include "archive_command.h"
#include "command.h"
#include "inertest/serve/server.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string db;
  serve::ServerOptions options;
};

CommandAction setup(CLI::App& root) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = root.add_subcommand(
      "serve",
      "Serve the results archive over HTTP until interrupted: a JSON API under /api/ giving the objects\n"
      "the archive commands print with --json (/api/campaigns, /api/campaigns/ID, /api/instruments,\n"
      "/api/instruments/ID/history?figure=P/F, /api/fleet?figure=P/F&since=DATE). Read-only and on the\n"
      "loopback interface unless told otherwise; prints its URL (and, with --allow-add, its token) at start.");
  add_db_option(*command, arguments->db);
  command->add_option("--bind", arguments->options.bind, "the address to listen on")->capture_default_str();
  command->add_option("--port", arguments->options.port, "the port (0: any free one)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  command->add_flag("--allow-add", arguments->options.allow_add,
                    "accept results.json files by POST /api/campaigns with the token printed at start "
                    "(header Authorization: Bearer TOKEN)");
  command->add_option("--max-body", arguments->options.max_body_bytes, "the largest request body accepted, bytes")
      ->capture_default_str();
  return [arguments] {
    arguments->options.db = arguments->db.empty() ? archive::default_archive_location() : arguments->db;
    // Ctrl-C or SIGTERM stops the server as stop() does: no new connection, the requests under way
    // answered (an add finishes its transaction), then exit 0. The signals are blocked in every
    // thread (the server's take this mask) and taken by one thread that waits for them.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);
    serve::Server server(arguments->options);
    fmt::print("inertest serve: {} ({})\n", server.url(), arguments->options.allow_add ? "adding allowed" : "read-only");
    if (arguments->options.allow_add) fmt::print("token: {}\n", server.token());
    std::fflush(stdout);
    std::atomic<bool> served{false};
    std::atomic<int> received{0};
    std::thread signal_waiter([&] {
      int signal = 0;
      sigwait(&signals, &signal);
      received = signal;
      // A stop() before run() listens would be lost: repeated until run() returns.
      while (!served) {
        server.stop();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    });
    server.run();
    served = true;
    if (received == 0) pthread_kill(signal_waiter.native_handle(), SIGTERM);  // run() ended on its own
    signal_waiter.join();
    if (received != 0) fmt::print(stderr, "inertest serve: stopped ({})\n", received == SIGINT ? "SIGINT" : "SIGTERM");
    return 0;
  };
}

const bool registered = register_command("serve", setup);

}  // namespace
}  // namespace inertest::cli
