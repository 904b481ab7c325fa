// The embedded back-end: one SQLite file in WAL mode (readers never block the writer), with a
// busy timeout so that several stations adding at once wait for the write lock in turn. A file
// this process cannot write (the file, or its directory where WAL keeps its -wal and -shm files:
// an archive shared read-only, `inertest serve` run by a service account) is opened read-only.
#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>
#include <fmt/format.h>

#include "archive/database.h"
#include "inertest/archive/archive.h"
#include "inertest/core/error.h"

namespace inertest::archive {
namespace {

// How long a writer waits for another's transaction before giving up, in ms. An add is a few
// hundred rows; a minute covers dozens of stations adding at once.
constexpr int busy_timeout_ms = 60000;

class SqliteDatabase final : public Database {
 public:
  explicit SqliteDatabase(const std::string& path) : path_(path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ignored;
    if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
    const std::string directory = parent.empty() ? "." : parent.string();
    read_only_ = std::filesystem::exists(path, ignored) &&
                 (::access(path.c_str(), W_OK) != 0 || ::access(directory.c_str(), W_OK) != 0);
    if (read_only_) {
      open_read_only();
    } else {
      open(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
    }
    try {
      sqlite3_busy_timeout(db_, busy_timeout_ms);
      sqlite3_extended_result_codes(db_, 1);
      std::vector<std::string> tables;
      for (const auto& row : query("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name", {})) {
        tables.push_back(row.text(0));
      }
      refuse_foreign_database(tables, path);
      if (!read_only_) enter_wal_mode();
      query("PRAGMA foreign_keys=ON", {});
      query("PRAGMA synchronous=FULL", {});
    } catch (...) {
      sqlite3_close(db_);  // the destructor does not run for a constructor that throws
      throw;
    }
  }
  ~SqliteDatabase() override { sqlite3_close(db_); }
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  std::vector<Row> query(std::string_view sql, const std::vector<Value>& params) override {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db_, sql.data(), static_cast<int>(sql.size()), &statement, nullptr) != SQLITE_OK) fail();
    std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> owner(statement, sqlite3_finalize);
    for (std::size_t i = 0; i < params.size(); ++i) {
      // $N is a named parameter to SQLite: look its index up rather than trust the order.
      const std::string name = fmt::format("${}", i + 1);
      const int index = sqlite3_bind_parameter_index(statement, name.c_str());
      if (index == 0) continue;
      int status = SQLITE_OK;
      if (const auto* text = std::get_if<std::string>(&params[i])) {
        status = sqlite3_bind_text(statement, index, text->data(), static_cast<int>(text->size()), SQLITE_TRANSIENT);
      } else if (const auto* real = std::get_if<double>(&params[i])) {
        status = sqlite3_bind_double(statement, index, *real);
      } else if (const auto* integer = std::get_if<std::int64_t>(&params[i])) {
        status = sqlite3_bind_int64(statement, index, *integer);
      } else {
        status = sqlite3_bind_null(statement, index);
      }
      if (status != SQLITE_OK) fail();
    }
    std::vector<Row> rows;
    for (;;) {
      const int status = sqlite3_step(statement);
      if (status == SQLITE_DONE) break;
      if (status != SQLITE_ROW) fail();
      Row row;
      for (int c = 0; c < sqlite3_column_count(statement); ++c) {
        switch (sqlite3_column_type(statement, c)) {
          case SQLITE_INTEGER: row.columns.emplace_back(static_cast<std::int64_t>(sqlite3_column_int64(statement, c))); break;
          case SQLITE_FLOAT: row.columns.emplace_back(sqlite3_column_double(statement, c)); break;
          case SQLITE_NULL: row.columns.emplace_back(std::monostate{}); break;
          default:
            row.columns.emplace_back(std::string(reinterpret_cast<const char*>(sqlite3_column_text(statement, c)),
                                                 static_cast<std::size_t>(sqlite3_column_bytes(statement, c))));
        }
      }
      rows.push_back(std::move(row));
    }
    return rows;
  }

  void begin(bool exclusive) override { query(exclusive ? "BEGIN IMMEDIATE" : "BEGIN", {}); }
  void commit() override { query("COMMIT", {}); }
  void rollback() noexcept override { sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr); }
  std::string backend() const override { return "sqlite"; }
  bool read_only() const override { return read_only_; }

 private:
  void open(const std::string& name, int flags) {
    if (sqlite3_open_v2(name.c_str(), &db_, flags | SQLITE_OPEN_FULLMUTEX, nullptr) != SQLITE_OK) {
      const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      db_ = nullptr;
      throw DatabaseError(SourceLocation{path_, 0, 0}, "cannot open the archive: " + message);
    }
  }

  // mode=ro reads a WAL file as any reader does, but needs its -shm file: one a writer has open, or
  // one it can make. Where neither is (a closed archive in a directory it cannot write), the file is
  // read as it stands (immutable=1: no locks, no -shm): what the last writer checkpointed, which a
  // writer that closes cleanly has done with everything.
  void open_read_only() {
    std::string uri = "file:";
    for (const char c : path_) {
      if (c == '%' || c == '?' || c == '#') {
        uri += fmt::format("%{:02X}", static_cast<unsigned char>(c));
      } else {
        uri += c;
      }
    }
    open(uri + "?mode=ro", SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
    if (sqlite3_exec(db_, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr) == SQLITE_OK) return;
    sqlite3_close(db_);
    db_ = nullptr;
    open(uri + "?immutable=1", SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
  }

  // Turning a new file to WAL takes an exclusive lock, and SQLite answers SQLITE_BUSY at once,
  // without the busy handler, while another station opens the same new file: retry until the
  // busy timeout (seen with 8 stations adding to a new archive at once under the sanitizers).
  void enter_wal_mode() {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(busy_timeout_ms);
    for (;;) {
      const int status = sqlite3_exec(db_, "PRAGMA journal_mode=WAL", nullptr, nullptr, nullptr);
      if (status == SQLITE_OK) return;
      const int primary = status & 0xff;
      if ((primary != SQLITE_BUSY && primary != SQLITE_LOCKED) || std::chrono::steady_clock::now() > deadline) fail();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }

  [[noreturn]] void fail() const {
    throw DatabaseError(SourceLocation{path_, 0, 0}, std::string("archive: ") + sqlite3_errmsg(db_));
  }

  std::string path_;
  sqlite3* db_ = nullptr;
  bool read_only_ = false;
};

}  // namespace

std::unique_ptr<Database> open_sqlite(const std::string& path) { return std::make_unique<SqliteDatabase>(path); }

}  // namespace inertest::archive
