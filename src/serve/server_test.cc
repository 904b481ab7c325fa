// inertest serve over loopback: each API route gives exactly the CLI's --json object, and hostile
// requests get a 4xx JSON error and leave the archive file byte for byte as it was.
#include "inertest/serve/server.h"

#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/archive/archive.h"
#include "inertest/core/error.h"
#include "serve/pages.h"
#include "test_util/scale_factor_campaign.h"
#include "test_util/test_util.h"

namespace inertest::serve {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// An HTTP answer read off the socket.
struct Reply {
  int status = 0;
  std::string body;
  nlohmann::json json() const { return nlohmann::json::parse(body); }
};

// Sends request (its bytes exactly, so hostile paths reach the server unchanged) and reads the
// answer.
Reply http_exchange(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return {};
  }
  for (std::size_t sent = 0; sent < request.size();) {
    const auto n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  // Until the body is complete (Content-Length), or the server closes the connection.
  std::string text;
  const auto complete = [&text] {
    const auto end = text.find("\r\n\r\n");
    const auto length = text.find("Content-Length: ");
    return end != std::string::npos && length != std::string::npos && length < end &&
           text.size() >= end + 4 + std::stoul(text.substr(length + 16));
  };
  char buffer[65536];
  for (ssize_t n; !complete() && (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) {
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  Reply reply;
  if (text.rfind("HTTP/1.1 ", 0) == 0) reply.status = std::stoi(text.substr(9, 3));
  if (const auto end = text.find("\r\n\r\n"); end != std::string::npos) reply.body = text.substr(end + 4);
  return reply;
}

Reply get(int port, const std::string& target) {
  return http_exchange(port, "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
}

Reply post(int port, const std::string& target, const std::string& body, const std::string& headers = "",
           const std::string& type = "application/json") {
  return http_exchange(port, "POST " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" + headers +
                            "Content-Type: " + type + "\r\nContent-Length: " + std::to_string(body.size()) +
                            "\r\n\r\n" + body);
}

std::string file_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), {}};
}

// An archive of the golden demo campaign (FOG-SIM-NAV, every procedure) and three scale factor
// tests of two more gyros, served on a free loopback port for the test's lifetime.
class ServeApi : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = scratch_.path() + "/archive.sqlite";
    nlohmann::json demo = archive::read_results_file(testing::source_path("tests/golden/demo_results.json"));
    demo["tested_on"] = "2026-03-02";
    demo["processed_at"] = "2026-03-02T08:00:00Z";
    {
      const auto store = archive::open_archive(db_);
      store->add(demo, "demo_results.json");
      store->add(testing::scale_factor_campaign("FOG-2", "2026-03-01", 36000.4), "FOG-2");
      store->add(testing::scale_factor_campaign("FOG-3", "2026-03-01", 35999.8), "FOG-3");
      store->add(testing::scale_factor_campaign("FOG-3", "2026-03-03", 35999.9), "FOG-3");
      demo_id_ = store->list(std::string("FOG-SIM-NAV")).at(0).id;
    }
    demo_ = demo;
  }
  void TearDown() override { stop(); }

  void start(bool allow_add) {
    ServerOptions options;
    options.db = db_;
    options.port = 0;
    options.allow_add = allow_add;
    options.max_body_bytes = 64 * 1024;
    server_ = std::make_unique<Server>(options);
    thread_ = std::thread([this] { server_->run(); });
  }
  void stop() {
    if (!server_) return;
    server_->stop();
    thread_.join();
    server_.reset();
  }
  int port() const { return server_->port(); }
  nlohmann::json cli_json(std::vector<std::string> arguments) const {
    arguments.insert(arguments.end(), {"--db", db_, "--json"});
    const auto run = testing::run_cli(arguments);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out);
  }

  testing::ScratchDirectory scratch_;
  std::string db_;
  std::string demo_id_;
  nlohmann::json demo_;
  std::unique_ptr<Server> server_;
  std::thread thread_;
};

TEST_F(ServeApi, EveryRouteGivesTheCommandLinesJson) {
  start(false);
  EXPECT_EQ(server_->url(), "http://127.0.0.1:" + std::to_string(port()) + "/");

  const auto campaigns = get(port(), "/api/campaigns");
  ASSERT_EQ(campaigns.status, 200) << campaigns.body;
  EXPECT_EQ(campaigns.json(), cli_json({"archive", "list"}));
  EXPECT_EQ(campaigns.json()["campaigns"].size(), 4u);

  const auto instruments = get(port(), "/api/instruments");
  ASSERT_EQ(instruments.status, 200) << instruments.body;
  EXPECT_EQ(instruments.json(), cli_json({"archive", "instruments"}));
  const nlohmann::json instrument_list = instruments.json();
  const auto& fog3 = instrument_list["instruments"][1];
  EXPECT_EQ(fog3["instrument"], "FOG-3");
  EXPECT_EQ(fog3["campaigns"], 2);
  EXPECT_EQ(fog3["latest"]["tested_on"], "2026-03-03");
  EXPECT_EQ(instrument_list["instruments"][2]["latest"]["verdict"], "FAIL");  // the demo's

  for (const std::string figure : {"scale_factor/scale_factor", "bias_static/bias"}) {
    const auto history = get(port(), "/api/instruments/FOG-SIM-NAV/history?figure=" + figure);
    ASSERT_EQ(history.status, 200) << history.body;
    EXPECT_EQ(history.json(), cli_json({"archive", "history", "FOG-SIM-NAV", "--figure", figure}));
  }

  const auto fleet = get(port(), "/api/fleet?figure=scale_factor/scale_factor");
  ASSERT_EQ(fleet.status, 200) << fleet.body;
  EXPECT_EQ(fleet.json(), cli_json({"archive", "fleet", "--figure", "scale_factor/scale_factor"}));
  EXPECT_EQ(fleet.json()["instruments"].size(), 3u);
  const auto since = get(port(), "/api/fleet?figure=scale_factor/scale_factor&since=2026-03-02");
  ASSERT_EQ(since.status, 200) << since.body;
  EXPECT_EQ(since.json(),
            cli_json({"archive", "fleet", "--figure", "scale_factor/scale_factor", "--since", "2026-03-02"}));
  // The fleet page counts from the date too, and says so (it showed the whole fleet).
  const std::size_t counted = since.json()["instruments"].size();
  ASSERT_LT(counted, 3u);
  const auto row = [](const std::string& page) {
    const auto at = page.find("<tr><td>scale_factor/scale_factor</td>");
    return at == std::string::npos ? std::string() : page.substr(at, page.find("</tr>", at) - at);
  };
  const auto whole_page = get(port(), "/fleet");
  const auto since_page = get(port(), "/fleet?since=2026-03-02");
  ASSERT_EQ(since_page.status, 200) << since_page.body;
  EXPECT_THAT(row(whole_page.body), HasSubstr("</td><td>3</td>"));
  EXPECT_THAT(row(since_page.body), HasSubstr(fmt::format("</td><td>{}</td>", counted)));
  EXPECT_THAT(since_page.body, HasSubstr("<p class=\"since\">Tests on or after: 2026-03-02</p>"));
  EXPECT_THAT(whole_page.body, Not(HasSubstr("class=\"since\"")));
  EXPECT_EQ(get(port(), "/fleet?since=2026-3-2").status, 400);

  const auto results = get(port(), "/api/campaigns/" + demo_id_);
  ASSERT_EQ(results.status, 200) << results.body;
  EXPECT_EQ(results.json(), demo_);
}

// A plan names its steps in words ("Scale factor at 20 degC", every example plan does): their
// figures answered 400 "the figure is malformed", and the history page's own links with them.
TEST_F(ServeApi, FiguresOfStepsNamedInWords) {
  nlohmann::json campaign = testing::scale_factor_campaign("FOG-4", "2026-03-04", 36000.1);
  campaign["procedures"][0]["name"] = "Scale factor at 20 degC";
  campaign["verdicts"][0]["procedure"] = "Scale factor at 20 degC";
  archive::open_archive(db_)->add(campaign, "FOG-4");
  start(false);
  const std::string figure = "Scale factor at 20 degC/scale_factor";
  const auto history = get(port(), "/api/instruments/FOG-4/history?figure=Scale%20factor%20at%2020%20degC/scale_factor");
  ASSERT_EQ(history.status, 200) << history.body;
  EXPECT_EQ(history.json(), cli_json({"archive", "history", "FOG-4", "--figure", figure}));
  const auto fleet = get(port(), "/api/fleet?figure=Scale+factor+at+20+degC/scale_factor");
  ASSERT_EQ(fleet.status, 200) << fleet.body;
  EXPECT_EQ(fleet.json(), cli_json({"archive", "fleet", "--figure", figure}));
  EXPECT_EQ(get(port(), "/instruments/FOG-4?figure=Scale%20factor%20at%2020%20degC/scale_factor").status, 200);
  // The instrument switcher keeps the figure shown; an instrument without it shows its whole page,
  // saying so (it was a bare JSON 404).
  const auto other = get(port(), "/instruments/FOG-4?figure=bias/bias");
  EXPECT_EQ(other.status, 200);
  EXPECT_THAT(other.body, ::testing::HasSubstr("FOG-4 has no history of figure bias/bias; all its figures follow."));
  EXPECT_THAT(other.body, ::testing::HasSubstr("Scale factor at 20 degC/scale_factor"));
}

// Each hostile request gets a 4xx with {"error": ...}; the server goes on serving and the
// archive file is byte-identical afterwards.
TEST_F(ServeApi, HostileRequestsGet4xxAndChangeNothing) {
  const std::string before = file_bytes(db_);
  start(false);
  const std::vector<std::pair<std::string, int>> targets = {
      // Any text is an id or a figure the archive may hold (bound to the query, never spliced): these
      // are unknown.
      {"/api/instruments/FOG-2'%20OR%20'1'='1/history?figure=scale_factor/scale_factor", 404},
      {"/api/instruments/FOG-2%27%3B%20DROP%20TABLE%20campaign%3B--/history?figure=scale_factor/scale_factor", 404},
      {"/api/instruments/FOG%092/history?figure=scale_factor/scale_factor", 400},
      {"/api/instruments/FOG-2/history?figure=scale_factor/x'%20OR%201%3D1--", 404},
      {"/api/fleet?figure=scale_factor/scale_factor'%3BDELETE%20FROM%20figure%3B--", 404},
      {"/api/fleet?figure=scale_factor%0A/scale_factor", 400},
      {"/api/fleet?figure=scale_factor//scale_factor", 400},
      {"/api/fleet?figure=scale_factor", 400},
      {"/api/fleet?figure=scale_factor/scale_factor&since=2026'--", 400},
      {"/api/campaigns/0'%20OR%20'1'='1", 400},
      {"/api/campaigns/" + std::string(16, 'x'), 400},
      {"/api/campaigns/0123456789abcdef", 404},
      {"/api/instruments/NO-SUCH/history?figure=scale_factor/scale_factor", 404},
      {"/api/instruments/FOG-2/history?figure=scale_factor/no_such", 404},
      {"/api/instruments/FOG-2/history", 400},
      {"/api/instruments/%2e%2e/history?figure=scale_factor/scale_factor", 400},
      {"/api/instruments/FOG-2/history?figure=../../etc/passwd", 400},
      {"/api/instruments/FOG-2/history?figure=scale_factor/%2e%2e", 400},
      {"/api/fleet", 400},
      {"/../../etc/passwd", 404},
      {"/api/%2e%2e/%2e%2e/etc/passwd", 404},
      {"/api/", 404},
      {"/api/nothing", 404},
      {"/campaigns/..%2f..%2fetc%2fpasswd", 404},
      {"/instruments/%2e%2e", 400},
  };
  for (const auto& [target, status] : targets) {
    const auto reply = get(port(), target);
    EXPECT_EQ(reply.status, status) << target << ": " << reply.body;
    ASSERT_NO_THROW(EXPECT_TRUE(reply.json().at("error").is_string()) << target) << target << ": " << reply.body;
  }
  // Adding is refused by a read-only server, token or not, and a malformed request line too.
  EXPECT_EQ(post(port(), "/api/campaigns", testing::scale_factor_campaign("FOG-9", "2026-04-01", 36000.0).dump()).status, 403);
  EXPECT_EQ(post(port(), "/api/campaigns", std::string(70 * 1024, ' ')).status, 403);  // read-only first, not 413
  const auto garbage = http_exchange(port(), "NONSENSE\r\n\r\n");
  EXPECT_EQ(garbage.status, 400);
  EXPECT_TRUE(garbage.json().contains("error"));
  EXPECT_EQ(get(port(), "/api/campaigns").status, 200);
  stop();
  EXPECT_EQ(file_bytes(db_), before);
}

// With --allow-add a results.json is added by POST only with the token, within the size limit,
// valid JSON and valid results; anything else is refused and changes nothing.
TEST_F(ServeApi, AddingNeedsTheTokenAndAValidBodyWithinTheLimit) {
  const std::string before = file_bytes(db_);
  start(true);
  ASSERT_EQ(server_->token().size(), 32u);
  const auto list = get(port(), "/");
  EXPECT_NE(list.body.find("<form id=\"add-form\""), std::string::npos);
  EXPECT_EQ(list.body.find(server_->token()), std::string::npos);  // the page never holds the token
  const std::string token = "Authorization: Bearer " + server_->token() + "\r\n";
  const std::string good = testing::scale_factor_campaign("FOG-9", "2026-04-01", 36000.0).dump();
  EXPECT_EQ(post(port(), "/api/campaigns", good).status, 401);
  EXPECT_EQ(post(port(), "/api/campaigns", good, "Authorization: Bearer 0123\r\n").status, 403);
  // A form upload (curl -F) is no results.json: 415, not an internal error; no body at all is
  // answered at once (it waited for the read timeout).
  EXPECT_EQ(post(port(), "/api/campaigns", "--x\r\n\r\n--x--\r\n", token, "multipart/form-data; boundary=x").status, 415);
  const auto bodiless = http_exchange(port(), "POST /api/campaigns HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" +
                                                  token + "\r\n");
  EXPECT_EQ(bodiless.status, 400) << bodiless.body;
  { const auto big = post(port(), "/api/campaigns", std::string(70 * 1024, ' ') + good, token); EXPECT_EQ(big.status, 413) << big.body; }
  EXPECT_EQ(post(port(), "/api/campaigns", "{\"instrument\": ", token).status, 400);
  EXPECT_EQ(post(port(), "/api/campaigns", "[1, 2, 3]", token).status, 400);
  nlohmann::json not_a_number = testing::scale_factor_campaign("FOG-9", "2026-04-01", 36000.0);
  not_a_number["procedures"][0]["result"]["scale_factor"]["value"] = "36000";
  EXPECT_EQ(post(port(), "/api/campaigns", not_a_number.dump(), token).status, 400);
  EXPECT_EQ(file_bytes(db_), before);

  // The scheme's name in any case (RFC 7235): "bearer" is Bearer.
  std::string lower_case = token;
  lower_case.replace(lower_case.find("Bearer"), 6, "bearer");
  const auto added = post(port(), "/api/campaigns", good, lower_case);
  ASSERT_EQ(added.status, 200) << added.body;
  EXPECT_EQ(added.json()["added"][0]["instrument"], "FOG-9");
  EXPECT_TRUE(added.json()["added"][0]["added"].get<bool>());
  EXPECT_FALSE(post(port(), "/api/campaigns", good, token).json()["added"][0]["added"].get<bool>());
  EXPECT_EQ(get(port(), "/api/campaigns").json()["campaigns"].size(), 5u);
  // In chunks past --max-body (64 KiB here): refused, not kept whole in memory.
  const std::string chunk(40 * 1024, ' ');
  const auto chunked = http_exchange(port(), "POST /api/campaigns HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" +
                                                 token + "Transfer-Encoding: chunked\r\n\r\na000\r\n" + chunk +
                                                 "\r\na000\r\n" + chunk + "\r\n0\r\n\r\n");
  EXPECT_EQ(chunked.status, 413) << chunked.body;
  // As `curl --data-binary @results.json` sends it, a form: a body over cpp-httplib's 8 KiB of form.
  nlohmann::json large = testing::scale_factor_campaign("FOG-10", "2026-04-02", 36000.0);
  large["plan"] = {{"notes", std::string(20 * 1024, 'x')}};
  const auto as_form = post(port(), "/api/campaigns", large.dump(), token, "application/x-www-form-urlencoded");
  ASSERT_EQ(as_form.status, 200) << as_form.body;
  EXPECT_EQ(as_form.json()["added"][0]["instrument"], "FOG-10");
}

// Results the archive refuses are the client's fault, a 400 naming what is wrong, never a 500 or a
// crash: two steps of one name (the same figure twice: a UNIQUE constraint failed, 500), a number
// beyond a double (500), a nesting that exhausted the stack (the server crashed).
TEST_F(ServeApi, RefusedResultsAreA400) {
  const std::string before = file_bytes(db_);
  start(true);
  const std::string token = "Authorization: Bearer " + server_->token() + "\r\n";
  nlohmann::json twice = testing::scale_factor_campaign("FOG-9", "2026-04-01", 36000.0);
  twice["procedures"].push_back(twice["procedures"][0]);
  const auto duplicate = post(port(), "/api/campaigns", twice.dump(), token);
  EXPECT_EQ(duplicate.status, 400) << duplicate.body;
  EXPECT_NE(duplicate.json().value("error", "").find("appears twice"), std::string::npos) << duplicate.body;

  std::string overflow = testing::scale_factor_campaign("FOG-9", "2026-04-01", 36000.0).dump();
  overflow.replace(overflow.find("36000.0"), 7, "1e400");
  const auto huge = post(port(), "/api/campaigns", overflow, token);
  EXPECT_EQ(huge.status, 400) << huge.body;
  EXPECT_EQ(huge.json().value("error", ""), "the body is not valid JSON: number overflow parsing '1e400'");

  nlohmann::json deep = testing::scale_factor_campaign("FOG-9", "2026-04-01", 36000.0);
  deep["procedures"][0]["result"]["deep"] = "PLACEHOLDER";
  std::string nested;  // 8000 levels: within --max-body (64 KiB here)
  for (int i = 0; i < 8000; ++i) nested += "{\"a\":";
  nested += "1" + std::string(8000, '}');
  std::string deep_body = deep.dump();
  deep_body.replace(deep_body.find("\"PLACEHOLDER\""), 13, nested);
  const auto crash = post(port(), "/api/campaigns", deep_body, token);
  EXPECT_EQ(crash.status, 400) << crash.body;
  EXPECT_NE(crash.json().value("error", "").find("nested more than 64 levels deep"), std::string::npos) << crash.body;
  EXPECT_EQ(get(port(), "/api/campaigns").status, 200);  // still serving
  stop();
  EXPECT_EQ(file_bytes(db_), before);
}

// A date that is no day is the query's fault, named as the parameter (it was a 404 naming the
// command line's --since); a method other than GET and POST is a 405, not a 400 or 404.
TEST_F(ServeApi, ABadDateIsA400AndAnOtherMethodA405) {
  start(false);
  for (const std::string date : {"2026-13-45", "2026-02-30", "2026-04-04x", "2026-04-04T00:00:00Z"}) {
    const auto reply = get(port(), "/api/fleet?figure=scale_factor/scale_factor&since=" + date);
    EXPECT_EQ(reply.status, 400) << date << ": " << reply.body;
    EXPECT_EQ(reply.json().value("error", ""), "the query parameter 'since' is not a date YYYY-MM-DD") << date;
  }
  for (const std::string method : {"PUT", "DELETE", "PATCH"}) {
    for (const std::string target : {"/api/campaigns", "/api/instruments", "/"}) {
      const auto reply = http_exchange(port(), method + " " + target +
                                                   " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n"
                                                   "Content-Length: 2\r\n\r\n{}");
      EXPECT_EQ(reply.status, 405) << method << " " << target << ": " << reply.body;
      EXPECT_TRUE(reply.json().contains("error")) << reply.body;
    }
  }
}

// Idle connections (opened, no request sent) do not hold up a request: with cpp-httplib's 8
// threads, 20 of them kept every other client waiting about 10 s. The answer is awaited for at
// most 4 s (the default keep-alive alone held a thread 5 s).
TEST_F(ServeApi, IdleConnectionsDoNotStallOthers) {
  start(false);
  std::vector<int> idle;
  for (int i = 0; i < 20; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port()));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    idle.push_back(fd);
  }
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port()));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval limit{4, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
  ASSERT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  const std::string request = "GET /api/instruments HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  ASSERT_EQ(::send(fd, request.data(), request.size(), MSG_NOSIGNAL), static_cast<ssize_t>(request.size()));
  char buffer[16] = {};
  const auto n = ::recv(fd, buffer, sizeof buffer - 1, 0);
  EXPECT_GT(n, 0) << "no answer within 4 s while 20 connections are idle";
  EXPECT_EQ(std::string(buffer).rfind("HTTP/1.1 200", 0), 0u) << buffer;
  ::close(fd);
  for (const int socket : idle) ::close(socket);
}

// An IPv6 address is written in brackets in the URL the server prints (http://::1:8080/ is no URL).
TEST(Serve, AnIpv6AddressIsBracketedInTheUrl) {
  testing::ScratchDirectory scratch;
  const std::string db = scratch.path() + "/archive.sqlite";
  archive::open_archive(db)->add(testing::scale_factor_campaign("FOG-2", "2026-03-01", 36000.4), "FOG-2");
  ServerOptions options;
  options.db = db;
  options.port = 0;
  options.bind = "::1";
  std::unique_ptr<Server> server;
  try {
    server = std::make_unique<Server>(options);
  } catch (const Error& e) {
    GTEST_SKIP() << "no IPv6 loopback here: " << e.what();
  }
  EXPECT_EQ(server->url(), "http://[::1]:" + std::to_string(server->port()) + "/");
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The report's pages carry each plot's data and the plots' script; the history page its switcher,
// and ?figure= narrows it to one figure. (tests/serve/check_serve_in_chromium.py runs the script.)
TEST_F(ServeApi, PagesCarryThePlotsDataAndScript) {
  start(false);
  for (const std::string& page : std::vector<std::string>{"/campaigns/" + demo_id_, "/instruments/FOG-SIM-NAV", "/fleet"}) {
    const auto reply = get(port(), page);
    ASSERT_EQ(reply.status, 200) << page;
    EXPECT_GT(count(reply.body, "<svg class=\"plot\""), 0u) << page;
    EXPECT_EQ(count(reply.body, "<svg class=\"plot\""), count(reply.body, "class=\"plot-data\"")) << page;
    EXPECT_EQ(count(reply.body, "window.inertestPlots = {"), 1u) << page;
    EXPECT_NE(reply.body.find("@media print { .plot-tools"), std::string::npos) << page;
  }

  const auto history = get(port(), "/instruments/FOG-3?lang=zh");
  ASSERT_EQ(history.status, 200);
  EXPECT_NE(history.body.find("<option value=\"/instruments/FOG-2?lang=zh\">FOG-2</option>"), std::string::npos);
  EXPECT_NE(history.body.find("<option value=\"/instruments/FOG-3?lang=zh\" selected>FOG-3</option>"), std::string::npos);
  EXPECT_NE(history.body.find("<option value=\"/instruments/FOG-3?figure=scale_factor/scale_factor&amp;lang=zh\">"),
            std::string::npos);

  const auto all = get(port(), "/instruments/FOG-SIM-NAV");
  const auto one = get(port(), "/instruments/FOG-SIM-NAV?figure=scale_factor/scale_factor");
  ASSERT_EQ(one.status, 200);
  EXPECT_GT(count(all.body, "<section class=\"procedure\">"), 1u);
  EXPECT_EQ(count(one.body, "<section class=\"procedure\">"), 1u);
  // An instrument without the figure: its whole page, saying so (the switcher keeps the figure).
  const auto without = get(port(), "/instruments/FOG-2?figure=bias_static/bias");
  EXPECT_EQ(without.status, 200);
  EXPECT_NE(without.body.find("id=\"figure-missing\""), std::string::npos);
  EXPECT_EQ(get(port(), "/instruments/FOG-2?figure=..%2Fx").status, 400);
  EXPECT_EQ(get(port(), "/favicon.ico").status, 204);
  EXPECT_EQ(get(port(), "/").body.find("add-form"), std::string::npos);  // read-only: no form to add
}

// The database failing under the running server (its file and WAL index overwritten with zeros, so
// that SQLite drops its cached pages and finds no database) is the server's failure, a 500 with a
// JSON error, not a 404 as if the instrument or campaign were unknown.
TEST_F(ServeApi, ADatabaseFailureIsA500NotA404) {
  start(false);
  ASSERT_EQ(get(port(), "/api/instruments").status, 200);
  for (const std::string& path : {db_, db_ + "-shm"}) {
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    const auto size = std::filesystem::file_size(path);
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    const std::string zeros(size, '\0');
    file.write(zeros.data(), static_cast<std::streamsize>(zeros.size()));
  }
  for (const std::string& target : std::vector<std::string>{"/api/instruments", "/api/campaigns/" + demo_id_,
                                                            "/api/instruments/FOG-3/history?figure=scale_factor/scale_factor",
                                                            "/instruments/FOG-3", "/"}) {
    const auto reply = get(port(), target);
    EXPECT_EQ(reply.status, 500) << target << ": " << reply.body;
    EXPECT_NE(reply.json().value("error", "").find("the archive's database failed"), std::string::npos) << reply.body;
  }
}

// Any id the archive takes opens in the web view: a space, a '/' and Chinese characters are
// percent-encoded in the links and read back from the path.
TEST_F(ServeApi, AnIdWithASpaceASlashOrChineseOpensItsPages) {
  const std::string id = "FOG 12/\xe9\x99\x80\xe8\x9e\xba";  // FOG 12/陀螺
  archive::open_archive(db_)->add(testing::scale_factor_campaign(id, "2026-03-04", 36000.1), "odd");
  start(false);
  const std::string encoded = "FOG%2012%2F%E9%99%80%E8%9E%BA";
  EXPECT_NE(get(port(), "/").body.find("<a href=\"/instruments/" + encoded + "\">"), std::string::npos);
  EXPECT_EQ(get(port(), "/instruments/" + encoded).status, 200);
  const auto history = get(port(), "/api/instruments/" + encoded + "/history?figure=scale_factor/scale_factor");
  ASSERT_EQ(history.status, 200) << history.body;
  EXPECT_EQ(history.json().at("instrument"), id);
}

// A port another server holds is an error, not a second listener the kernel would share the
// requests with (cpp-httplib's default SO_REUSEPORT allowed that).
TEST_F(ServeApi, APortInUseIsAnError) {
  start(false);
  ASSERT_EQ(get(port(), "/api/instruments").status, 200);  // running (a stop before it is lost)
  ServerOptions options;
  options.db = db_;
  options.port = port();
  EXPECT_THROW(Server second(options), Error);
}

// `inertest serve` stops on SIGTERM (or Ctrl-C) as stop() does, says so and exits 0.
TEST_F(ServeApi, TheCommandStopsOnASignalAndExitsZero) {
  int out[2];
  ASSERT_EQ(::pipe(out), 0);
  testing::ScratchDirectory scratch;
  const std::string err_path = scratch.path() + "/err";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::close(out[0]);
    if (!std::freopen(err_path.c_str(), "w", stderr)) _exit(127);
    const std::string program = testing::cli_path();
    ::execl(program.c_str(), program.c_str(), "serve", "--db", db_.c_str(), "--port", "0", nullptr);
    _exit(127);
  }
  ::close(out[1]);
  std::string first_line;
  char c = 0;
  while (::read(out[0], &c, 1) == 1 && c != '\n') first_line += c;
  ::close(out[0]);
  const auto colon = first_line.rfind(':');
  ASSERT_NE(colon, std::string::npos) << first_line;
  const int served_port = std::stoi(first_line.substr(colon + 1));
  EXPECT_EQ(get(served_port, "/api/instruments").status, 200);
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  std::ifstream err(err_path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(err), {}), "inertest serve: stopped (SIGTERM)\n");
}

TEST(Serve, MissingArchiveIsAnError) {
  testing::ScratchDirectory scratch;
  ServerOptions options;
  options.db = scratch.path() + "/none.sqlite";
  options.port = 0;
  EXPECT_THROW(Server server(options), Error);
}

// A figure of a step named with '&', '#', '+' or blanks links to its history: the query's value is
// percent-encoded ('&' ended it, '#' the query, and the server answered 400).
TEST(HistorySwitcher, FigureLinksArePercentEncoded) {
  const std::string page = with_history_switcher("<html><body><h1>x</h1></body></html>", {"FOG 1"}, "FOG 1",
                                                 {"SF & NL #1+x/nonlinearity"}, "", report::Language::english);
  EXPECT_NE(page.find("value=\"/instruments/FOG%201?figure=SF%20%26%20NL%20%231%2Bx/nonlinearity\""), std::string::npos)
      << page;
}

}  // namespace
}  // namespace inertest::serve
