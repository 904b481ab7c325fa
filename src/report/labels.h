// The report's words in English and Chinese (GJB 2426A-2004 terms), from one table (labels.cc).
// Keys: a figure or quantity is its JSON key ("bias_stability"); a procedure kind is "kind.<kind>";
// a method description is "method.<kind>"; page furniture is "ui.<word>"; an axis quantity is
// "axis.<quantity>". A key missing from the table reads as itself made readable
// ("bias_stability" -> "Bias stability"); Chinese falls back to the English entry.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "inertest/report/report.h"

namespace inertest::report {

class Labels {
 public:
  explicit Labels(Language language) : language_(language) {}
  Language language() const { return language_; }
  // The label for the key in this language: the table's, else that of "axis.<key>" (a curve's
  // member named as an axis quantity, "time", or with its unit, "phase_deg"), else the key made
  // readable (humanise_key).
  std::string operator()(std::string_view key) const;
  // A procedure's title: its spec's (procedure_spec.h), else the table's "kind.<kind>".
  std::string title_of(const std::string& kind) const;
  // A figure's label in a procedure's result: the spec's field label (capitalised), else the table's.
  std::string field_of(const std::string& kind, std::string_view key) const;
  // A procedure's method in one paragraph: its spec's; "" for none.
  std::string method_of(const std::string& kind) const;
  // Whether the table holds the key (in any language).
  static bool known(std::string_view key);
  // The key's place in the table (figures are listed in this order); keys not in it come last.
  static std::size_t rank(std::string_view key);
  // Every key of the table, in its order.
  static std::vector<std::string_view> keys();

 private:
  Language language_;
};

// "bias_stability" -> "Bias stability"; the part before a '.' prefix is dropped.
std::string humanise_key(std::string_view key);

}  // namespace inertest::report
