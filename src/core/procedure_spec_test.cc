// The procedure registry and the generic JSON and text writers (issue 22).
#include "inertest/core/procedure_spec.h"

#include <limits>
#include <set>

#include "test_util/test_util.h"

namespace inertest {
namespace {

TEST(ProcedureSpec, RegistryHoldsEveryDeclaredProcedureOnceWithUniqueNames) {
  const auto& specs = procedure_specs();
  ASSERT_NE(find_procedure_spec("polarity"), nullptr);
  EXPECT_EQ(find_procedure_spec("no_such_procedure"), nullptr);
  std::set<std::string> kinds;
  for (const ProcedureSpec& spec : specs) {
    EXPECT_TRUE(kinds.insert(spec.kind).second) << spec.kind;
    EXPECT_FALSE(spec.clause.empty()) << spec.kind;
    EXPECT_TRUE(spec.run) << spec.kind;
    // Flags, plan keys and JSON keys are made from these names: one of each.
    std::set<std::string> names;
    for (const auto& parameter : spec.parameters) {
      EXPECT_TRUE(names.insert(parameter.name).second) << spec.kind << " " << parameter.name;
      EXPECT_FALSE(parameter.doc.empty()) << spec.kind << " " << parameter.name;
    }
    for (const auto& input : spec.inputs) EXPECT_TRUE(names.insert(input.name).second) << spec.kind << " " << input.name;
    std::set<std::string> fields = {"procedure"};  // a field "clause" replaces the spec's (threshold's method)
    for (const auto& field : spec.fields) {
      EXPECT_TRUE(fields.insert(field.name).second) << spec.kind << " " << field.name;
      EXPECT_FALSE(field.label_en.empty()) << spec.kind << " " << field.name;
      EXPECT_FALSE(field.label_zh.empty()) << spec.kind << " " << field.name;
    }
  }
}

TEST(ProcedureSpec, AParameterErrorNamesTheParameterAsItsCallerDoes) {
  EXPECT_EQ(ParameterError("interval_s", "interval_s must be positive").message_naming("--interval"),
            "--interval must be positive");
  EXPECT_EQ(ParameterError("table_rate", "must be nonzero with method 3").message_naming("table_rate_deg_s"),
            "table_rate_deg_s: must be nonzero with method 3");
}

TEST(ProcedureSpec, KebabCase) {
  EXPECT_EQ(kebab_case("nonlinearity_limit"), "nonlinearity-limit");
  EXPECT_EQ(kebab_case("polarity"), "polarity");
}

ProcedureSpec example_spec() {
  ProcedureSpec spec;
  spec.kind = "example";
  spec.json_procedure = "example";
  spec.title = "Example";
  spec.clause = "GJB 2426A-2004 5.0";
  spec.fields = {{"figure", FieldRole::headline, "figure", "示例", ""},
                 {"flag", FieldRole::detail, "flag", "标志", ""},
                 {"missing", FieldRole::detail, "missing", "缺", ""},
                 {"hidden", FieldRole::hidden, "hidden", "隐", ""},
                 {"rows", FieldRole::table, "rows", "表", ""},
                 {"warnings", FieldRole::hidden, "warnings", "警告", ""}};
  return spec;
}

TEST(ProcedureSpec, JsonHasProcedureClauseAndTheFieldsThatAreNotNull) {
  const nlohmann::json fields = {{"figure", {{"value", 1.5}, {"unit", "ppm"}}}, {"missing", nullptr}, {"flag", true}};
  const nlohmann::json json = procedure_json(example_spec(), fields);
  EXPECT_EQ(json, (nlohmann::json{{"procedure", "example"},
                                  {"clause", "GJB 2426A-2004 5.0"},
                                  {"figure", {{"value", 1.5}, {"unit", "ppm"}}},
                                  {"flag", true}}));
}

// A figure that overflowed (NaN, Inf) is an error naming where it is, not a null in the JSON.
TEST(ProcedureSpec, ANonFiniteNumberAnywhereInTheFieldsIsAnError) {
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    nlohmann::json fields = nlohmann::json::object();
    fields["figure"] = nlohmann::json{{"value", 1.5}, {"unit", "ppm"}};
    fields["curve"] = nlohmann::json::array({nlohmann::json{{"x", 1.0}, {"y", 2.0}}, nlohmann::json{{"x", 2.0}, {"y", bad}}});
    try {
      procedure_json(example_spec(), fields);
      ADD_FAILURE() << "a non-finite number was written";
    } catch (const Error& e) {
      EXPECT_EQ(e.message(), "example: /curve/1/y is not a finite number: the data overflow a double (give them in a "
                             "larger unit)");
    }
  }
}

TEST(ProcedureSpec, TextPrintsEveryShownFieldTheSameWay) {
  const nlohmann::json fields = {{"figure", {{"value", 1.5}, {"unit", "ppm"}, {"uncertainty", 0.25}}},
                                 {"flag", false},
                                 {"hidden", "x"},
                                 {"rows", {{{"rate", 100.0}, {"meets", true}}, {{"rate", 200.0}, {"meets", false}}}},
                                 {"warnings", {"only 2 runs"}}};
  EXPECT_EQ(procedure_text(example_spec(), fields),
            "Example (GJB 2426A-2004 5.0)\n"
            "  figure                           1.5 ± 0.25 ppm\n"
            "  flag                             no\n"
            "  rows\n"
            "    meets yes, rate 100\n"
            "    meets no, rate 200\n"
            "  warning: only 2 runs\n");
  // A cell that is a table of its own follows its row, a row a line (it was raw JSON); plain numbers
  // read to 9 digits, as figures.
  const nlohmann::json nested = {{"rows", {{{"rate", 100.0}, {"points", {{{"output", 1.0 / 3.0}}, {{"output", 2.0}}}}}}}};
  EXPECT_EQ(procedure_text(example_spec(), nested),
            "Example (GJB 2426A-2004 5.0)\n"
            "  rows\n"
            "    points (2 below), rate 100\n"
            "      points:\n"
            "        output 0.333333333\n"
            "        output 2\n");
}

// The polarity spec runs the procedure and names its fields as the JSON contract has them.
TEST(ProcedureSpec, PolarityFieldsFromTheSpec) {
  const ProcedureSpec& spec = *find_procedure_spec("polarity");
  ProcedureCall call;
  call.inputs = {{"positive", {12.0, std::nullopt}}, {"negative", {8.0, std::nullopt}}};
  call.parameters = {{"output_unit", "V"}, {"expected", "positive"}};
  const nlohmann::json json = procedure_json(spec, spec.run(call).fields);
  EXPECT_EQ(json.at("polarity"), "positive");
  EXPECT_EQ(json.at("sign").at("value"), 1.0);
  EXPECT_EQ(json.at("output_positive_rate").at("unit"), "V");
  EXPECT_EQ(json.at("output_sign_negative_rate"), "positive");
  EXPECT_FALSE(json.at("signs_opposite").get<bool>());
  EXPECT_TRUE(json.at("pass").get<bool>());
  EXPECT_EQ(json.at("warnings").size(), 1u);
  call.parameters = nlohmann::json::object();
  EXPECT_FALSE(procedure_json(spec, spec.run(call).fields).contains("pass"));
}

}  // namespace
}  // namespace inertest
