// Reading one table of a TOML test plan with strict checking: every key must be read by the
// procedure it belongs to (an unknown key is an error naming its line), every value must have the
// expected type, and data files are resolved against the plan's directory and must exist.
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "inertest/core/error.h"

namespace inertest::campaign {

class PlanTable {
 public:
  PlanTable(const toml::table& table, std::string plan_path, std::string plan_dir, std::string where);

  // Required and optional values of each type; wrong types are errors naming the line.
  double number(std::string_view key);
  std::optional<double> optional_number(std::string_view key);
  double number_or(std::string_view key, double fallback);
  std::string string(std::string_view key);
  std::optional<std::string> optional_string(std::string_view key);
  std::string string_or(std::string_view key, std::string fallback);
  bool boolean_or(std::string_view key, bool fallback);
  // A day of the Gregorian calendar, as "YYYY-MM-DD": a TOML date (2026-03-04) or a string of that
  // form; anything else ("last tuesday", 2026-02-30, a time of day) is an error naming the line.
  std::optional<std::string> optional_date(std::string_view key);
  std::vector<double> numbers(std::string_view key);  // an array of numbers
  std::optional<std::vector<double>> optional_numbers(std::string_view key);
  std::vector<std::string> strings(std::string_view key);
  // A data file: the path relative to the plan's directory; the file must exist.
  std::string file(std::string_view key);
  std::optional<std::string> optional_file(std::string_view key);
  std::vector<std::string> files(std::string_view key);
  // A data file resolved as by `file`, and the path as the plan wrote it (lexically normal): its
  // name in results, the same whichever directory the plan is run from.
  struct NamedFile {
    std::string path;
    std::string as_written;
  };
  NamedFile named_file(std::string_view key);
  std::vector<NamedFile> named_files(std::string_view key);
  // A nested table (e.g. [procedure.options]).
  std::optional<PlanTable> optional_table(std::string_view key);
  // An array of tables (e.g. [[procedure.run]]).
  std::vector<PlanTable> tables(std::string_view key);
  bool contains(std::string_view key) const;

  // Throws Error for the first key that was never read.
  void require_all_used() const;

  // An Error located at this table, or at the given key within it.
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_at(std::string_view key, const std::string& message) const;
  // Where the key is in the plan, or the table when it has no such key.
  SourceLocation location_of_key(std::string_view key) const { return location_of(table_->get(key)); }

  // Every data file the plan's tables have resolved so far (file, files, optional_file), with where
  // it is named; shared by a table and the tables inside it.
  using DataFiles = std::vector<std::pair<std::string, SourceLocation>>;
  const DataFiles& data_files() const { return *data_files_; }

  const std::string& plan_path() const { return plan_path_; }
  const std::string& plan_dir() const { return plan_dir_; }
  const toml::table& raw() const { return *table_; }

 private:
  const toml::node* find(std::string_view key);
  SourceLocation location_of(const toml::node* node) const;
  NamedFile resolve(const toml::node* node, std::string_view key) const;

  const toml::table* table_;
  std::string plan_path_;
  std::string plan_dir_;
  std::string where_;  // e.g. "procedure 3 (bias)"
  std::set<std::string, std::less<>> used_;
  std::shared_ptr<DataFiles> data_files_ = std::make_shared<DataFiles>();
};

}  // namespace inertest::campaign
