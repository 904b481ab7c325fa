// Power consumption, GJB 2426A-2004 5.4 (功耗): "measure the input power that each power supply of
// the gyro needs" (5.4.1) with voltage and current meters, supplying it as 4.1.3 prescribes, and
// "record the input power each supply provides" (5.4.3). Declared once (issue 22): the command
// `inertest power-consumption`, the plan kind "power_consumption", the JSON, the text, the report
// and the Python function all come from this file.
//
// The readings: a CSV with the header 'supply,voltage,current' (V and A; other columns ignored),
// one row per reading, several rows of one supply being repeated readings in steady state. The
// input power of a supply is the mean of its readings' products P = U I (5.4.3: the power each
// supply provides), with the standard error of that mean, s / sqrt(n), when it has two readings
// or more; the power consumption is the sum over the supplies, its uncertainty the root sum of
// squares (the supplies are read independently). A negative rail reads a negative voltage and a
// negative current: a reading whose product is negative is an error at its line.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/io/mapped_file.h"
#include "inertest/io/text_table.h"
#include "inertest/numerics/statistics.h"

namespace inertest {
namespace {

struct PowerConsumptionOptions {};

// The readings of one supply, in the order of the file.
struct SupplyReadings {
  std::string supply;
  std::vector<double> voltage_v;
  std::vector<double> current_a;
};

struct SupplyPower {
  std::string supply;
  std::size_t readings = 0;
  Figure voltage;
  Figure current;
  Figure power;
};

struct PowerConsumptionResult {
  Figure power_consumption;
  std::vector<SupplyPower> supplies;
  std::vector<std::string> warnings;
};

double cell_number(const TextField& cell, const std::string& path, std::size_t line, const char* column) {
  const char* begin = cell.text.data();
  const char* end = begin + cell.text.size();
  if (begin != end && *begin == '+') ++begin;
  double value = 0.0;
  const auto parsed = std::from_chars(begin, end, value);
  if (cell.text.empty() || parsed.ec != std::errc() || parsed.ptr != end || !std::isfinite(value)) {
    throw Error(SourceLocation{path, line, cell.column}, fmt::format("{}: '{}' is not a number", column, cell.text));
  }
  return value;
}

// The supplies in the order they first appear; throws Error at file:line:column.
std::vector<SupplyReadings> read_supply_readings(const std::string& path) {
  const MappedFile file(path);
  const std::string_view text = file.text();
  constexpr std::size_t kColumns = 3;
  constexpr const char* kNames[kColumns] = {"supply", "voltage", "current"};
  std::array<std::size_t, kColumns> index{};
  std::size_t header_fields = 0;
  std::vector<SupplyReadings> supplies;
  std::size_t line_number = 0;  // of the last row read, for the message of a file without readings
  for (const TextCellRow& row : split_text_cells(text, path)) {
    line_number = row.line;
    const std::vector<TextField>& cells = row.cells;
    if (header_fields == 0) {
      for (std::size_t k = 0; k < kColumns; ++k) {
        const auto found = std::find_if(cells.begin(), cells.end(), [&](const TextField& c) { return c.text == kNames[k]; });
        if (found == cells.end()) {
          throw Error(SourceLocation{path, line_number, 1},
                      fmt::format("expected a header row naming the columns 'supply', 'voltage' (V) and 'current' "
                                  "(A); '{}' is missing",
                                  kNames[k]));
        }
        index[k] = static_cast<std::size_t>(found - cells.begin());
      }
      header_fields = cells.size();
      continue;
    }
    if (cells.size() != header_fields) {
      throw Error(SourceLocation{path, line_number, 1},
                  fmt::format("{} columns, but the header has {}", cells.size(), header_fields));
    }
    const TextField& name = cells[index[0]];
    if (name.text.empty()) throw Error(SourceLocation{path, line_number, name.column}, "supply: empty name");
    const double voltage = cell_number(cells[index[1]], path, line_number, "voltage");
    const double current = cell_number(cells[index[2]], path, line_number, "current");
    if (voltage * current < 0.0) {
      throw Error(SourceLocation{path, line_number, cells[index[2]].column},
                  fmt::format("voltage {} V and current {} A have opposite signs, a negative input power (a "
                              "negative rail reads both negative)",
                              voltage, current));
    }
    auto supply = std::find_if(supplies.begin(), supplies.end(), [&](const SupplyReadings& s) { return s.supply == name.text; });
    if (supply == supplies.end()) supply = supplies.insert(supplies.end(), SupplyReadings{name.text, {}, {}});
    supply->voltage_v.push_back(voltage);
    supply->current_a.push_back(current);
  }
  if (supplies.empty()) throw Error(SourceLocation{path, line_number, 0}, "no readings");
  return supplies;
}

// The mean of the values and, from two values on, its standard error s / sqrt(n).
Figure mean_figure(const std::vector<double>& values, const std::string& unit) {
  if (values.size() < 2) return {mean(values), unit, std::nullopt};
  return {mean(values), unit, sample_standard_deviation(values) / std::sqrt(static_cast<double>(values.size()))};
}

PowerConsumptionResult power_consumption(const std::vector<SupplyReadings>& readings) {
  PowerConsumptionResult result;
  double total = 0.0;
  double variance = 0.0;
  bool every_uncertainty = true;
  for (const SupplyReadings& supply : readings) {
    std::vector<double> power(supply.voltage_v.size());
    for (std::size_t i = 0; i < power.size(); ++i) power[i] = supply.voltage_v[i] * supply.current_a[i];
    SupplyPower row{supply.supply, power.size(), mean_figure(supply.voltage_v, "V"),
                    mean_figure(supply.current_a, "A"), mean_figure(power, "W")};
    total += row.power.value;
    if (!row.power.uncertainty) {
      every_uncertainty = false;
      result.warnings.push_back(fmt::format("supply '{}' has one reading: its power has no uncertainty", supply.supply));
    } else if (is_constant(power)) {
      result.warnings.push_back(fmt::format(
          "the {} readings of supply '{}' are all equal: the uncertainty 0 is the meters' resolution, not the "
          "supply's",
          power.size(), supply.supply));
    } else if (power.size() - 1 < kFewDegreesOfFreedom) {
      // s/sqrt(n) from few readings held the mean power in 50 % of trials at n = 2.
      result.warnings.push_back(fmt::format(
          "supply '{}' has {} readings: the 1-sigma of its power, estimated from so few, holds the true mean in about "
          "{:.0f} % of tests, not 68 % (Student's t)",
          supply.supply, power.size(), 100.0 * one_sigma_coverage(static_cast<double>(power.size() - 1))));
    }
    // +5 V and -5 V readings under one name are two rails: their mean voltage of 0 is no supply's.
    const auto [lowest, highest] = std::minmax_element(supply.voltage_v.begin(), supply.voltage_v.end());
    if (*lowest < 0.0 && *highest > 0.0) {
      result.warnings.push_back(fmt::format("supply '{}' reads both positive and negative voltages ({} V to {} V): two "
                                            "rails under one name? its mean voltage, current and power are no "
                                            "rail's, and the total counts one rail where there are two",
                                            supply.supply, *lowest, *highest));
    }
    variance += row.power.uncertainty.value_or(0.0) * row.power.uncertainty.value_or(0.0);
    result.supplies.push_back(std::move(row));
  }
  result.power_consumption = {total, "W", every_uncertainty ? std::optional<double>(std::sqrt(variance)) : std::nullopt};
  return result;
}

nlohmann::json supplies_json(const PowerConsumptionResult& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const SupplyPower& s : result.supplies) {
    rows.push_back({{"supply", s.supply},
                    {"readings", s.readings},
                    {"voltage", s.voltage},
                    {"current", s.current},
                    {"power", s.power}});
  }
  return rows;
}

}  // namespace

ProcedureSpec power_consumption_spec();

ProcedureSpec power_consumption_spec() {
  return ProcedureDefinition<PowerConsumptionOptions, PowerConsumptionResult>(
             "power_consumption", "Power consumption", "GJB 2426A-2004 5.4",
             "the input power of each power supply, P = U I (the mean over its readings, with its\n"
             "standard error from two readings on), and their sum. SUPPLIES is a CSV with the header\n"
             "'supply,voltage,current' (V, A): one row per reading, repeated rows of a supply being\n"
             "readings in steady state; a negative rail reads a negative voltage and current.")
      .chinese_title("功耗")
      .report_method(
          "Each power supply's voltage and current are read with meters while the gyro runs on the supply "
          "conditions of 4.1.3; the input power of a supply is the mean of its readings' products U·I, with the "
          "standard error of that mean, and the power consumption is their sum.",
          "按 4.1.3 规定的供电条件给陀螺供电，用电压、电流测量设备读取每种电源的电压和电流；每种电源的输入功率为其各次读数 U·I "
          "的平均值（附平均值的标准误差），功耗为各电源输入功率之和。")
      .example({"examples/power_consumption/supplies.csv"})
      .input(InputSpec("supplies", "CSV of voltage and current readings per supply").read_from_file("SUPPLIES", "file"))
      .field({"power_consumption", FieldRole::headline, "power consumption", "功耗", "GJB 2426A-2004 5.4.3"},
             &PowerConsumptionResult::power_consumption)
      .field_from({"supplies", FieldRole::table, "input power per supply", "各电源输入功率", "GJB 2426A-2004 5.4.3"},
                  supplies_json)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &PowerConsumptionResult::warnings)
      .unit_of("power_consumption", "W")
      .compute([](const ProcedureCall& call, const PowerConsumptionOptions&) {
        return power_consumption(read_supply_readings(call.files.at("supplies")));
      });
}

}  // namespace inertest
