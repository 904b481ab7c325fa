// The shared back-end: a PostgreSQL server through libpq, for a lab whose stations share one
// archive. Parameters travel separately from the SQL text (PQexecParams), never spliced into it.
#include <libpq-fe.h>

#include <algorithm>
#include <string_view>

#include <fmt/format.h>

#include "archive/database.h"
#include "inertest/archive/archive.h"
#include "inertest/core/error.h"

namespace inertest::archive {
namespace {

// The advisory lock that serialises schema migrations (and any exclusive transaction) across
// every process using the same database; an arbitrary constant, "inertest" in ASCII.
constexpr const char* advisory_lock_sql = "SELECT pg_advisory_xact_lock(7597131758597743476)";

}  // namespace

std::string redact_postgresql_url(const std::string& url) {
  std::string redacted = url;
  // ?password=... or &password=...: the value up to the next parameter.
  for (std::size_t at = redacted.find('?'); at != std::string::npos; at = redacted.find('&', at + 1)) {
    static constexpr std::string_view key = "password=";
    if (redacted.compare(at + 1, key.size(), key) != 0) continue;
    const std::size_t value = at + 1 + key.size();
    const std::size_t end = std::min(redacted.find('&', value), redacted.size());
    redacted.replace(value, end - value, "***");
  }
  // user:password@host
  const auto scheme_end = redacted.find("://");
  const auto authority_end = scheme_end == std::string::npos ? std::string::npos : redacted.find_first_of("/?", scheme_end + 3);
  const auto at = redacted.rfind('@', authority_end == std::string::npos ? redacted.size() : authority_end);
  if (scheme_end == std::string::npos || at == std::string::npos || at < scheme_end) return redacted;
  const auto colon = redacted.find(':', scheme_end + 3);
  if (colon == std::string::npos || colon > at) return redacted;
  return redacted.substr(0, colon) + ":***" + redacted.substr(at);
}

namespace {

class PostgresqlDatabase final : public Database {
 public:
  explicit PostgresqlDatabase(const std::string& url) : where_(redact_postgresql_url(url)) {
    // A server that accepts and never answers would hang every command: 10 s to connect, unless
    // the URL says otherwise (its connect_timeout comes later and wins).
    const char* keywords[] = {"connect_timeout", "dbname", nullptr};
    const char* values[] = {"10", url.c_str(), nullptr};
    connection_ = PQconnectdbParams(keywords, values, 1);
    if (connection_ == nullptr || PQstatus(connection_) != CONNECTION_OK) {
      const std::string message = connection_ ? PQerrorMessage(connection_) : "out of memory";
      PQfinish(connection_);
      throw DatabaseError(SourceLocation{where_, 0, 0}, "cannot open the archive: " + trim(message));
    }
    // CREATE ... IF NOT EXISTS and the like send notices; they are not the user's business.
    PQsetNoticeProcessor(connection_, [](void*, const char*) {}, nullptr);
    try {
      std::vector<std::string> tables;
      for (const auto& row : query("SELECT table_name FROM information_schema.tables WHERE table_schema = "
                                   "current_schema() ORDER BY table_name",
                                   {})) {
        tables.push_back(row.text(0));
      }
      refuse_foreign_database(tables, where_);
    } catch (...) {
      PQfinish(connection_);  // the destructor does not run for a constructor that throws
      throw;
    }
  }
  ~PostgresqlDatabase() override { PQfinish(connection_); }
  PostgresqlDatabase(const PostgresqlDatabase&) = delete;
  PostgresqlDatabase& operator=(const PostgresqlDatabase&) = delete;

  std::vector<Row> query(std::string_view sql, const std::vector<Value>& params) override {
    std::vector<std::string> texts(params.size());
    std::vector<const char*> values(params.size(), nullptr);
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (const auto* text = std::get_if<std::string>(&params[i])) {
        texts[i] = *text;
      } else if (const auto* real = std::get_if<double>(&params[i])) {
        texts[i] = fmt::format("{}", *real);  // shortest text that reads back to the same double
      } else if (const auto* integer = std::get_if<std::int64_t>(&params[i])) {
        texts[i] = std::to_string(*integer);
      } else {
        continue;  // SQL NULL
      }
      values[i] = texts[i].c_str();
    }
    const std::string statement(sql);
    const auto execute = [&] {
      return std::unique_ptr<PGresult, void (*)(PGresult*)>(
          PQexecParams(connection_, statement.c_str(), static_cast<int>(params.size()), nullptr, values.data(), nullptr,
                       nullptr, 0),
          PQclear);
    };
    auto result = execute();
    ExecStatusType status = result ? PQresultStatus(result.get()) : PGRES_FATAL_ERROR;
    // The connection broke (the server restarted, an idle connection was cut): connect again once
    // and repeat the statement, unless it was inside a transaction, whose work went with the
    // connection (the transaction fails; the next one finds the connection restored).
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK && PQstatus(connection_) == CONNECTION_BAD &&
        !in_transaction_) {
      PQreset(connection_);
      if (PQstatus(connection_) == CONNECTION_OK) {
        PQsetNoticeProcessor(connection_, [](void*, const char*) {}, nullptr);
        result = execute();
        status = result ? PQresultStatus(result.get()) : PGRES_FATAL_ERROR;
      }
    }
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
      throw DatabaseError(SourceLocation{where_, 0, 0}, "archive: " + trim(PQerrorMessage(connection_)));
    }
    std::vector<Row> rows;
    for (int r = 0; r < PQntuples(result.get()); ++r) {
      Row row;
      for (int c = 0; c < PQnfields(result.get()); ++c) {
        if (PQgetisnull(result.get(), r, c)) {
          row.columns.emplace_back(std::monostate{});
        } else {
          row.columns.emplace_back(std::string(PQgetvalue(result.get(), r, c),
                                               static_cast<std::size_t>(PQgetlength(result.get(), r, c))));
        }
      }
      rows.push_back(std::move(row));
    }
    return rows;
  }

  void begin(bool exclusive) override {
    query("BEGIN", {});
    in_transaction_ = true;
    if (exclusive) query(advisory_lock_sql, {});
  }
  void commit() override {
    query("COMMIT", {});
    in_transaction_ = false;
  }
  void rollback() noexcept override {
    in_transaction_ = false;
    PGresult* result = PQexec(connection_, "ROLLBACK");
    PQclear(result);
  }
  std::string backend() const override { return "postgresql"; }

 private:
  static std::string trim(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
  }

  std::string where_;
  PGconn* connection_ = nullptr;
  bool in_transaction_ = false;  // between begin() and commit() or rollback()
};

}  // namespace

std::unique_ptr<Database> open_postgresql(const std::string& url) { return std::make_unique<PostgresqlDatabase>(url); }

}  // namespace inertest::archive
