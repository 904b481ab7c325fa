// The one thing a back-end of the archive provides: parameterised SQL on one connection, and
// transactions. The schema and every query are written once (archive.cc) in the SQL that SQLite
// and PostgreSQL share, with parameters written $1, $2, ... (both engines accept that syntax).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace inertest::archive {

// A parameter or a column value. PostgreSQL returns text; SQLite its stored type. The accessors
// convert, so callers never see the difference.
using Value = std::variant<std::monostate, std::int64_t, double, std::string>;

struct Row {
  std::vector<Value> columns;
  bool is_null(std::size_t i) const { return std::holds_alternative<std::monostate>(columns.at(i)); }
  std::string text(std::size_t i) const;
  double real(std::size_t i) const;
  std::optional<double> optional_real(std::size_t i) const;
  std::int64_t integer(std::size_t i) const;
};

class Database {
 public:
  virtual ~Database() = default;
  // Runs one statement with its parameters bound ($1 is params[0]); returns the rows it yields.
  // Throws Error with the engine's message.
  virtual std::vector<Row> query(std::string_view sql, const std::vector<Value>& params = {}) = 0;
  // Opens a transaction that holds the write lock from its start (SQLite BEGIN IMMEDIATE;
  // PostgreSQL BEGIN plus a transaction-scoped advisory lock when exclusive is set), so that
  // concurrent writers queue instead of failing.
  virtual void begin(bool exclusive) = 0;
  virtual void commit() = 0;
  virtual void rollback() noexcept = 0;
  virtual std::string backend() const = 0;
  // The connection can read but not write (a file this process cannot write): the archive is read
  // as it is, neither migrated nor added to.
  virtual bool read_only() const { return false; }
};

std::unique_ptr<Database> open_sqlite(const std::string& path);
std::unique_ptr<Database> open_postgresql(const std::string& url);

// url with its password, given as user:password@ or as a password= parameter, replaced by ***:
// what messages show.
std::string redact_postgresql_url(const std::string& url);

// A database is the archive's to migrate when it is empty or holds the archive's schema (a
// schema_version table): given the names of its tables, throws Error naming location otherwise, so
// that a mistyped --db naming another program's database is refused before anything in it (its
// tables, SQLite's journal mode) is changed.
void refuse_foreign_database(const std::vector<std::string>& tables, const std::string& location);

// Rolls back on scope exit unless committed: an exception anywhere in an add leaves nothing behind.
class Transaction {
 public:
  Transaction(Database& db, bool exclusive) : db_(db) { db_.begin(exclusive); }
  ~Transaction() {
    if (!done_) db_.rollback();
  }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit() {
    db_.commit();
    done_ = true;
  }

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace inertest::archive
