// The shared back-end: a PostgreSQL server through libpq, for a lab whose stations share one
// archive. Parameters travel separately from the SQL text (PQexecParams), never spliced into it.
#include <libpq-fe.h>

#include <fmt/format.h>

#include "archive/database.h"
#include "inertest/archive/archive.h"
#include "inertest/core/error.h"

namespace inertest::archive {
namespace {

// The advisory lock that serialises schema migrations (and any exclusive transaction) across
// every process using the same database; an arbitrary constant, "inertest" in ASCII.
constexpr const char* advisory_lock_sql = "SELECT pg_advisory_xact_lock(7597131758597743476)";

// The URL without its password, for messages.
std::string redact(const std::string& url) {
  const auto scheme_end = url.find("://");
  const auto at = url.find('@');
  if (scheme_end == std::string::npos || at == std::string::npos || at < scheme_end) return url;
  const auto colon = url.find(':', scheme_end + 3);
  if (colon == std::string::npos || colon > at) return url;
  return url.substr(0, colon) + ":***" + url.substr(at);
}

class PostgresqlDatabase final : public Database {
 public:
  explicit PostgresqlDatabase(const std::string& url) : where_(redact(url)) {
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
    std::unique_ptr<PGresult, void (*)(PGresult*)> result(
        PQexecParams(connection_, statement.c_str(), static_cast<int>(params.size()), nullptr, values.data(), nullptr,
                     nullptr, 0),
        PQclear);
    const ExecStatusType status = result ? PQresultStatus(result.get()) : PGRES_FATAL_ERROR;
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
    if (exclusive) query(advisory_lock_sql, {});
  }
  void commit() override { query("COMMIT", {}); }
  void rollback() noexcept override {
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
};

}  // namespace

std::unique_ptr<Database> open_postgresql(const std::string& url) { return std::make_unique<PostgresqlDatabase>(url); }

}  // namespace inertest::archive
