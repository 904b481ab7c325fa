#include "campaign/plan_table.h"

#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <utility>

#include "inertest/core/calendar_date.h"

namespace inertest::campaign {

PlanTable::PlanTable(const toml::table& table, std::string plan_path, std::string plan_dir, std::string where)
    : table_(&table), plan_path_(std::move(plan_path)), plan_dir_(std::move(plan_dir)), where_(std::move(where)) {}

SourceLocation PlanTable::location_of(const toml::node* node) const {
  const auto& begin = (node != nullptr ? node->source() : table_->source()).begin;
  return {plan_path_, static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)};
}

void PlanTable::fail(const std::string& message) const { throw Error(location_of(nullptr), where_ + ": " + message); }

void PlanTable::fail_at(std::string_view key, const std::string& message) const {
  throw Error(location_of(table_->get(key)), where_ + ": '" + std::string(key) + "' " + message);
}

bool PlanTable::contains(std::string_view key) const { return table_->contains(key); }

const toml::node* PlanTable::find(std::string_view key) {
  used_.emplace(key);
  return table_->get(key);
}

double PlanTable::number(std::string_view key) {
  const auto value = optional_number(key);
  if (!value) fail("missing required key '" + std::string(key) + "' (a number)");
  return *value;
}

std::optional<double> PlanTable::optional_number(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  if (const auto* f = node->as_floating_point()) {
    // TOML's nan and inf are no test's quantity: an infinite duration or rate was allocated (the
    // simulator's internal error), a nan limit failed every figure.
    if (!std::isfinite(f->get())) fail_at(key, "must be a finite number (not nan or inf)");
    return f->get();
  }
  if (const auto* i = node->as_integer()) return static_cast<double>(i->get());
  fail_at(key, "must be a number");
}

double PlanTable::number_or(std::string_view key, double fallback) { return optional_number(key).value_or(fallback); }

std::string PlanTable::string(std::string_view key) {
  auto value = optional_string(key);
  if (!value) fail("missing required key '" + std::string(key) + "' (a string)");
  return *value;
}

std::optional<std::string> PlanTable::optional_string(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  if (const auto* s = node->as_string()) return s->get();
  fail_at(key, "must be a string");
}

std::string PlanTable::string_or(std::string_view key, std::string fallback) {
  return optional_string(key).value_or(std::move(fallback));
}

bool PlanTable::boolean_or(std::string_view key, bool fallback) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  if (const auto* b = node->as_boolean()) return b->get();
  fail_at(key, "must be true or false");
}

std::optional<std::string> PlanTable::optional_date(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  std::optional<std::chrono::year_month_day> day;
  if (const auto* date = node->as_date()) {
    const toml::date value = date->get();
    day = std::chrono::year_month_day{std::chrono::year{value.year}, std::chrono::month{value.month},
                                      std::chrono::day{value.day}};
    if (!day->ok()) day.reset();
  } else if (const auto* s = node->as_string()) {
    day = parse_calendar_date(s->get());
  } else {
    fail_at(key, "must be a date, YYYY-MM-DD");
  }
  if (!day) {
    const std::string given = node->as_string() ? "'" + node->as_string()->get() + "'" : "the date given";
    fail_at(key, "must be a day of the calendar written YYYY-MM-DD (e.g. 2026-03-04), not " + given);
  }
  return fmt::format("{:04}-{:02}-{:02}", static_cast<int>(day->year()), static_cast<unsigned>(day->month()),
                     static_cast<unsigned>(day->day()));
}

std::optional<std::vector<double>> PlanTable::optional_numbers(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const auto* array = node->as_array();
  if (array == nullptr) fail_at(key, "must be an array of numbers");
  std::vector<double> values;
  for (const auto& element : *array) {
    if (const auto* f = element.as_floating_point()) {
      if (!std::isfinite(f->get())) {
        throw Error(location_of(&element), where_ + ": '" + std::string(key) + "' must hold finite numbers (not nan or inf)");
      }
      values.push_back(f->get());
    } else if (const auto* i = element.as_integer()) {
      values.push_back(static_cast<double>(i->get()));
    } else {
      throw Error(location_of(&element), where_ + ": '" + std::string(key) + "' must hold only numbers");
    }
  }
  return values;
}

std::vector<double> PlanTable::numbers(std::string_view key) {
  auto values = optional_numbers(key);
  if (!values) fail("missing required key '" + std::string(key) + "' (an array of numbers)");
  return *values;
}

std::vector<std::string> PlanTable::strings(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) fail("missing required key '" + std::string(key) + "' (an array of strings)");
  const auto* array = node->as_array();
  if (array == nullptr) fail_at(key, "must be an array of strings");
  std::vector<std::string> values;
  for (const auto& element : *array) {
    const auto* s = element.as_string();
    if (s == nullptr) throw Error(location_of(&element), where_ + ": '" + std::string(key) + "' must hold only strings");
    values.push_back(s->get());
  }
  return values;
}

PlanTable::NamedFile PlanTable::resolve(const toml::node* node, std::string_view key) const {
  const auto* s = node->as_string();
  if (s == nullptr) fail_at(key, "must be a file path (a string)");
  std::filesystem::path path(s->get());
  if (path.is_relative()) path = std::filesystem::path(plan_dir_) / path;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw Error(location_of(node), where_ + ": data file '" + s->get() + "' not found (looked for " +
                                       path.string() + ")");
  }
  data_files_->emplace_back(path.lexically_normal().string(), location_of(node));
  return {path.lexically_normal().string(), std::filesystem::path(s->get()).lexically_normal().string()};
}

std::string PlanTable::file(std::string_view key) { return named_file(key).path; }

PlanTable::NamedFile PlanTable::named_file(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) fail("missing required key '" + std::string(key) + "' (a data file)");
  return resolve(node, key);
}

std::optional<std::string> PlanTable::optional_file(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  return resolve(node, key).path;
}

std::vector<std::string> PlanTable::files(std::string_view key) {
  std::vector<std::string> paths;
  for (NamedFile& file : named_files(key)) paths.push_back(std::move(file.path));
  return paths;
}

std::vector<PlanTable::NamedFile> PlanTable::named_files(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) fail("missing required key '" + std::string(key) + "' (an array of data files)");
  const auto* array = node->as_array();
  if (array == nullptr) fail_at(key, "must be an array of file paths");
  std::vector<NamedFile> files;
  for (const auto& element : *array) files.push_back(resolve(&element, key));
  return files;
}

std::optional<PlanTable> PlanTable::optional_table(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const auto* table = node->as_table();
  if (table == nullptr) fail_at(key, "must be a table");
  PlanTable inner(*table, plan_path_, plan_dir_, where_ + "." + std::string(key));
  inner.data_files_ = data_files_;
  return inner;
}

std::vector<PlanTable> PlanTable::tables(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return {};
  const auto* array = node->as_array();
  if (array == nullptr || !array->is_array_of_tables()) fail_at(key, "must be an array of tables ([[...]])");
  std::vector<PlanTable> result;
  std::size_t index = 0;
  for (const auto& element : *array) {
    result.emplace_back(*element.as_table(), plan_path_, plan_dir_,
                        where_ + "." + std::string(key) + "[" + std::to_string(++index) + "]");
    result.back().data_files_ = data_files_;
  }
  return result;
}

void PlanTable::require_all_used() const {
  for (const auto& [key, node] : *table_) {
    if (!used_.contains(key.str())) {
      const auto& begin = key.source().begin.line > 0 ? key.source().begin : node.source().begin;
      throw Error(SourceLocation{plan_path_, static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)},
                  where_ + ": unknown key '" + std::string(key.str()) + "'");
    }
  }
}

}  // namespace inertest::campaign
