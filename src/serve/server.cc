// inertest serve's HTTP side: cpp-httplib routes onto the archive's queries; every object it
// returns is made by the library function the CLI's --json prints (archive/archive.h).
#include "inertest/serve/server.h"

#include <httplib.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <random>
#include <regex>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/archive/archive.h"
#include "inertest/core/error.h"
#include "inertest/core/json_text.h"
#include "inertest/report/archive_pages.h"
#include "inertest/report/report.h"
#include "inertest/report/svg_plot.h"
#include "serve/pages.h"

namespace inertest::serve {
namespace {

// A request the server refuses: its status (4xx) and what it says.
struct Refusal {
  int status;
  std::string message;
};

// Names are checked before any query: an instrument id as the archive takes it (any text; here no
// control character, not a dot segment, at most 256 bytes: it is only bound to queries and
// escaped in pages), a campaign id (16 hex digits, the archive's content hash), PROCEDURE/FIGURE
// keys as the archive takes them too (PROCEDURE is a plan's step name, "Scale factor at 20 degC":
// any text without '/'; no segment empty, "." or ".."); a date is a day of the calendar
// (archive::is_test_date).
const std::regex instrument_pattern(R"((?!\.\.?$)[^\x00-\x1f\x7f]+)");
const std::regex campaign_pattern(R"([0-9a-f]{16})");
const std::regex figure_pattern(R"((?!(.*/)?\.\.?(/|$))[^\x00-\x1f\x7f/]+(/[^\x00-\x1f\x7f/]+)+)");

const std::string& checked(const std::string& value, const std::regex& pattern, const char* what) {
  if (value.size() > 256 || !std::regex_match(value, pattern)) {
    throw Refusal{400, fmt::format("{} is malformed", what)};
  }
  return value;
}

std::string required_parameter(const httplib::Request& request, const char* name) {
  if (!request.has_param(name)) throw Refusal{400, fmt::format("the query parameter '{}' is missing", name)};
  return request.get_param_value(name);
}

// The query's 'since' (tests on or after it, YYYY-MM-DD), as the command line's --since.
std::optional<std::string> since_of(const httplib::Request& request) {
  if (!request.has_param("since")) return std::nullopt;
  std::string since = request.get_param_value("since");
  if (!archive::is_test_date(since)) throw Refusal{400, "the query parameter 'since' is not a date YYYY-MM-DD"};
  return since;
}

const char* reason(int status) {
  switch (status) {
    case 400: return "bad request";
    case 401: return "the token is missing";
    case 403: return "forbidden";
    case 404: return "no such resource";
    case 409: return "two quantities under one name";
    case 413: return "the request body is too large";
    case 414: return "the request URI is too long";
    default: return "the request was refused";
  }
}

void send_json(httplib::Response& response, int status, const nlohmann::json& json) {
  response.status = status;
  response.set_content(json_text(json), "application/json");
}

// ?lang=en (the default) or zh.
report::Language language_of(const httplib::Request& request) {
  if (!request.has_param("lang")) return report::Language::english;
  const std::string code = request.get_param_value("lang");
  if (code != "en" && code != "zh") throw Refusal{400, "lang must be en or zh"};
  return report::parse_language(code);
}

// a == b in a time that depends on their lengths only, not on where they first differ, so that a
// client cannot find the token a byte at a time by timing the refusals.
bool same_secret(const std::string& a, const std::string& b) {
  unsigned difference = a.size() == b.size() ? 0u : 1u;
  for (std::size_t i = 0; i < a.size(); ++i) {
    difference |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i % std::max<std::size_t>(b.size(), 1)]);
  }
  return difference == 0 && !b.empty();
}

std::string random_token() {
  std::random_device device;
  std::string token;
  for (int i = 0; i < 4; ++i) token += fmt::format("{:08x}", device());
  return token;
}

}  // namespace

struct Server::Impl {
  ServerOptions options;
  std::unique_ptr<archive::Archive> store;
  std::mutex store_mutex;  // the archive serves one request at a time
  std::string token = random_token();
  httplib::Server http;
  int port = 0;

  // Runs answer under the archive's lock: it returns the JSON to send with 200, or fills in the
  // response itself (a page) and returns null. A Refusal becomes its 4xx, a failure of the
  // database a 500, a figure of two quantities (NotOneQuantity) a 409, and any other archive Error
  // (an unknown instrument, figure or campaign) a 404.
  template <typename Answer>
  httplib::Server::Handler route(Answer answer) {
    return [this, answer](const httplib::Request& request, httplib::Response& response) {
      try {
        nlohmann::json json;
        {
          std::lock_guard lock(store_mutex);
          json = answer(request, response);
        }
        if (!json.is_null()) send_json(response, 200, json);
      } catch (const Refusal& refusal) {
        send_json(response, refusal.status, {{"error", refusal.message}});
      } catch (const archive::DatabaseError& e) {
        send_json(response, 500, {{"error", "the archive's database failed: " + e.message()}});
      } catch (const archive::NotOneQuantity& e) {
        send_json(response, 409, {{"error", e.message()}});  // it exists, as two quantities
      } catch (const Error& e) {
        send_json(response, 404, {{"error", e.message()}});
      }
    };
  }

  // The figures the history and fleet pages show: those some plan set limits on (every figure
  // when none has limits), as `archive report` chooses them.
  std::vector<std::string> page_figures() {
    std::vector<std::string> figures = store->figures(true);
    return figures.empty() ? store->figures(false) : figures;
  }

  // What the history page of instrument shows (archive::history_data of the page figures).
  nlohmann::json history_page_data(const std::string& instrument) {
    if (store->list(instrument).empty()) throw Refusal{404, "instrument '" + instrument + "' has no campaign in the archive"};
    return archive::history_data(*store, instrument, page_figures());
  }

  // The history page: every figure, or (?figure=P/F) the one chosen, under the switcher.
  std::string history_page(const httplib::Request& request, const std::string& instrument) {
    nlohmann::json data = history_page_data(instrument);
    std::vector<std::string> figures;
    for (const auto& f : data.at("figures")) figures.push_back(f.at("figure").get<std::string>());
    std::string figure;
    std::string missing;  // a figure asked for that the instrument has not: its page says so, whole
    if (request.has_param("figure")) {
      figure = checked(request.get_param_value("figure"), figure_pattern, "the figure");
      nlohmann::json chosen = nlohmann::json::array();
      for (const auto& f : data.at("figures")) {
        if (f.at("figure") == figure) chosen.push_back(f);
      }
      // The instrument switcher keeps the figure shown: another instrument without it landed on a
      // bare JSON 404. Its whole page, saying so, is where a reader wanted to go.
      if (chosen.empty()) {
        missing = std::exchange(figure, "");
      } else {
        data["figures"] = std::move(chosen);
      }
    }
    std::vector<std::string> instruments;
    const nlohmann::json listed = archive::instrument_list_json(store->list(std::nullopt));
    for (const auto& i : listed.at("instruments")) {
      instruments.push_back(i.at("instrument").get<std::string>());
    }
    const report::Language language = language_of(request);
    std::string page = with_history_switcher(report::render_history_page(data, page_options(request)), instruments,
                                             instrument, figures, figure, language);
    if (!missing.empty()) {
      const std::string text = language == report::Language::chinese
                                   ? fmt::format("{} 没有指标 {} 的历史记录；以下为其全部指标。", instrument, missing)
                                   : fmt::format("{} has no history of figure {}; all its figures follow.", instrument,
                                                 missing);
      const std::string note =
          fmt::format("<p class=\"note\" id=\"figure-missing\">{}</p>\n", report::escape_xml(text));
      constexpr std::string_view kNavEnd = "</nav>\n";  // the switcher's, after the page's header
      const std::size_t nav_end = page.find(kNavEnd);
      page.insert(nav_end == std::string::npos ? 0 : nav_end + kNavEnd.size(), note);
    }
    return with_interactive_plots(std::move(page));
  }

  // The report's options for a page: its language, today, and the plots' data for their script.
  static report::ReportOptions page_options(const httplib::Request& request) {
    report::ReportOptions options{language_of(request), report::current_date()};
    options.embed_plot_data = true;
    return options;
  }

  // `body` is null when it was over --max-body (not read): refused after who may add is checked.
  nlohmann::json add_campaign(const httplib::Request& request, const std::optional<std::string>& body) {
    if (!options.allow_add) throw Refusal{403, "the server is read-only (start it with --allow-add)"};
    const std::string authorization = request.get_header_value("Authorization");
    if (authorization.empty()) throw Refusal{401, "the token is missing (Authorization: Bearer TOKEN)"};
    // The scheme's name in any case (RFC 7235 2.1: "bearer" is Bearer), then the token itself.
    const std::size_t space = authorization.find(' ');
    std::string scheme = authorization.substr(0, space);
    std::transform(scheme.begin(), scheme.end(), scheme.begin(), [](unsigned char c) { return std::tolower(c); });
    if (scheme != "bearer" || space == std::string::npos || !same_secret(authorization.substr(space + 1), token)) {
      throw Refusal{403, "the token is wrong"};
    }
    if (!body) throw Refusal{413, reason(413)};
    nlohmann::json results;
    try {
      results = nlohmann::json::parse(*body);
    } catch (const nlohmann::json::parse_error&) {
      throw Refusal{400, "the body is not valid JSON"};
    } catch (const nlohmann::json::exception& e) {  // a number beyond a double: 1e400
      std::string message = e.what();
      if (const auto bracket = message.find("] "); bracket != std::string::npos) message.erase(0, bracket + 2);
      throw Refusal{400, "the body is not valid JSON: " + message};
    }
    try {
      archive::check_results(results, "request body");
    } catch (const Error& e) {
      throw Refusal{400, e.message()};
    }
    const archive::AddOutcome outcome = store->add(results, "request body");
    return {{"added", nlohmann::json::array({outcome.to_json("request body")})}};
  }

  void add_routes() {
    http.Get("/api/campaigns", route([this](const httplib::Request&, httplib::Response&) {
      return archive::campaign_list_json(store->list(std::nullopt));
    }));
    http.Get(R"(/api/campaigns/([^/]+))", route([this](const httplib::Request& request, httplib::Response&) {
      return store->results(checked(request.matches[1].str(), campaign_pattern, "the campaign id"));
    }));
    http.Get("/api/instruments", route([this](const httplib::Request&, httplib::Response&) {
      return archive::instrument_list_json(store->list(std::nullopt));
    }));
    http.Get(R"(/api/instruments/(.+)/history)", route([this](const httplib::Request& request, httplib::Response&) {
      const std::string instrument = checked(request.matches[1].str(), instrument_pattern, "the instrument id");
      const std::string figure = checked(required_parameter(request, "figure"), figure_pattern, "the figure");
      return store->history(instrument, figure).to_json();
    }));
    http.Get("/api/fleet", route([this](const httplib::Request& request, httplib::Response&) {
      const std::string figure = checked(required_parameter(request, "figure"), figure_pattern, "the figure");
      const std::optional<std::string> since = since_of(request);
      return archive::fleet_summary(store->fleet(figure, since), since);
    }));
    // The body is read here whatever its type: `curl --data-binary @results.json` sends a form,
    // which cpp-httplib would parse and cap at 8 KiB (a 413 for any real campaign).
    http.Post("/api/campaigns", [this](const httplib::Request& request, httplib::Response& response,
                                       const httplib::ContentReader& read) {
      // A body over --max-body is not kept: cpp-httplib skips one whose length says so, and one sent
      // in chunks is dropped once it passes the limit.
      const std::string length = request.get_header_value("Content-Length");
      // A form upload (curl -F) is no results.json: its reader is another (an internal error, 500).
      if (request.get_header_value("Content-Type").starts_with("multipart/form-data")) {
        route([](const httplib::Request&, httplib::Response&) -> nlohmann::json {
          throw Refusal{415, "the body must be a results.json itself (curl --data-binary @results.json), not a form "
                             "upload"};
        })(request, response);
        return;
      }
      std::optional<std::string> body;
      // Neither a length nor chunks: no body (waiting for one held a worker for the read timeout).
      if (length.empty() && request.get_header_value("Transfer-Encoding").find("chunked") == std::string::npos) {
        body.emplace();
      } else if (length.empty() || std::strtoull(length.c_str(), nullptr, 10) <= options.max_body_bytes) {
        body.emplace();
        read([&](const char* data, std::size_t size) {
          if (body && body->size() + size <= options.max_body_bytes) {
            body->append(data, size);
          } else {
            body.reset();
          }
          return true;
        });
      }
      route([this, &body](const httplib::Request& r, httplib::Response&) { return add_campaign(r, body); })(request,
                                                                                                          response);
    });

    // The pages, in English or (?lang=zh) Chinese.
    http.Get("/", route([this](const httplib::Request& request, httplib::Response& response) {
      response.set_content(render_instrument_list_page(archive::instrument_list_json(store->list(std::nullopt)),
                                                       language_of(request), options.allow_add),
                           "text/html; charset=utf-8");
      return nlohmann::json();
    }));
    http.Get(R"(/campaigns/([^/]+))", route([this](const httplib::Request& request, httplib::Response& response) {
      const auto results = store->results(checked(request.matches[1].str(), campaign_pattern, "the campaign id"));
      response.set_content(with_interactive_plots(report::render_report(results, page_options(request))),
                           "text/html; charset=utf-8");
      return nlohmann::json();
    }));
    http.Get(R"(/instruments/(.+))", route([this](const httplib::Request& request, httplib::Response& response) {
      const std::string instrument = checked(request.matches[1].str(), instrument_pattern, "the instrument id");
      response.set_content(history_page(request, instrument), "text/html; charset=utf-8");
      return nlohmann::json();
    }));
    http.Get("/fleet", route([this](const httplib::Request& request, httplib::Response& response) {
      const nlohmann::json data = archive::fleet_data(*store, page_figures(), since_of(request));
      response.set_content(with_interactive_plots(report::render_fleet_page(data.at("fleet"), page_options(request),
                                                                            data.at("not_comparable"))),
                           "text/html; charset=utf-8");
      return nlohmann::json();
    }));

    // The archive is read with GET and added to with POST: any other method is not allowed (405),
    // on a route that exists or not.
    const auto not_allowed = [](const httplib::Request& request, httplib::Response& response) {
      response.set_header("Allow", request.path == "/api/campaigns" ? "GET, POST" : "GET");
      send_json(response, 405, {{"error", "the method " + request.method + " is not allowed (GET reads; POST "
                                          "/api/campaigns adds a campaign)"}});
    };
    http.Put(".*", not_allowed);
    http.Patch(".*", not_allowed);
    http.Delete(".*", not_allowed);

    // No icon: an empty answer rather than a 404 in every browser's console.
    http.Get("/favicon.ico", [](const httplib::Request&, httplib::Response& response) { response.status = 204; });

    // Any 4xx without a body of its own (an unknown route, a body over the limit, a malformed
    // request line) gets the JSON error too.
    http.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& response) {
      if (!response.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
      send_json(response, response.status, {{"error", reason(response.status)}});
      return httplib::Server::HandlerResponse::Handled;
    }));
    http.set_exception_handler([](const httplib::Request&, httplib::Response& response, std::exception_ptr) {
      send_json(response, 500, {{"error", "internal error"}});
    });
    http.set_payload_max_length(options.max_body_bytes);
    // Each connection holds a thread while it waits for a request: with cpp-httplib's 8, 20 idle
    // connections (a browser's, a scanner's) kept every request waiting 10 s. 64 threads, and an idle
    // keep-alive connection closed after 2 s rather than 5.
    http.new_task_queue = [] { return new httplib::ThreadPool(64); };
    http.set_keep_alive_timeout(2);
    // An answer goes out as headers then body: without TCP_NODELAY the body waits for the client's
    // delayed ACK of the headers on a keep-alive connection (about 40 ms a request on Linux).
    http.set_tcp_nodelay(true);
    // SO_REUSEADDR only: cpp-httplib's default adds SO_REUSEPORT, with which a second server binds
    // the same port and the kernel splits the requests between the two archives.
    http.set_socket_options([](socket_t socket) {
      const int yes = 1;
      setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    http.set_default_headers({{"X-Content-Type-Options", "nosniff"}, {"Cache-Control", "no-store"}});
  }
};

Server::Server(const ServerOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->store = archive::open_archive(options.db, archive::ArchiveOpening::existing);
  impl_->add_routes();
  if (options.port == 0) {
    impl_->port = impl_->http.bind_to_any_port(options.bind);
    if (impl_->port < 0) impl_->port = 0;
  } else if (impl_->http.bind_to_port(options.bind, options.port)) {
    impl_->port = options.port;
  }
  if (impl_->port <= 0) throw Error(fmt::format("serve: cannot listen on {}:{}", options.bind, options.port));
}

Server::~Server() = default;

int Server::port() const { return impl_->port; }

std::string Server::url() const {
  const std::string& host = impl_->options.bind;
  // An IPv6 address goes in brackets (RFC 3986 3.2.2): http://[::1]:8080/.
  return fmt::format("http://{}:{}/", host.find(':') != std::string::npos ? "[" + host + "]" : host, impl_->port);
}

const std::string& Server::token() const { return impl_->token; }

void Server::run() { impl_->http.listen_after_bind(); }

void Server::stop() { impl_->http.stop(); }

}  // namespace inertest::serve
