// The polarity procedure's one description (issue 22): the CLI command `inertest polarity`, the plan
// kind "polarity", its JSON and its text report are all generated from it.
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/polarity.h"

namespace inertest {

ProcedureSpec polarity_spec() {
  return ProcedureDefinition<PolarityOptions, PolarityResult>(
             "polarity", "Polarity", "GJB 2426A-2004 5.7",
             "The sign of the output change for a positive input about the IRA, sign(F(+) - F(-)), from\n"
             "records (their means) or mean outputs at +rate and -rate.")
      .chinese_title("极性")
      .input({"positive", "the output at the positive rate"})
      .input({"negative", "the output at the negative rate"})
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &PolarityOptions::output_unit)
      .parameter(ParameterSpec("expected", "the specified polarity: positive or negative")
                     .one_of({"positive", "negative"}),
                 [](PolarityOptions& options, const nlohmann::json& value) {
                   options.expected = value.get<std::string>() == "positive" ? 1 : -1;
                 })
      .field_from({"polarity", FieldRole::headline, "polarity", "极性", "GJB 2426A-2004 5.7"},
                  [](const PolarityResult& r) { return r.polarity > 0 ? "positive" : "negative"; })
      .field_from({"sign", FieldRole::hidden, "sign", "符号", "sign(F(+) - F(-))"},
                  [](const PolarityResult& r) { return Figure{static_cast<double>(r.polarity), "1", std::nullopt}; })
      .field({"output_positive_rate", FieldRole::detail, "output at positive rate", "正向输入时输出", ""},
             &PolarityResult::output_positive_rate)
      .field({"output_negative_rate", FieldRole::detail, "output at negative rate", "负向输入时输出", ""},
             &PolarityResult::output_negative_rate)
      .field_from({"output_sign_positive_rate", FieldRole::detail, "output sign at positive rate", "正向输入时输出符号", ""},
                  [](const PolarityResult& r) { return output_sign_name(r.output_positive_rate.value); })
      .field_from({"output_sign_negative_rate", FieldRole::detail, "output sign at negative rate", "负向输入时输出符号", ""},
                  [](const PolarityResult& r) { return output_sign_name(r.output_negative_rate.value); })
      .field({"signs_opposite", FieldRole::hidden, "signs opposite", "符号相反", ""}, &PolarityResult::signs_opposite)
      .field_from({"pass", FieldRole::detail, "as specified", "符合规定", ""},
                  [](const PolarityResult& r) { return r.pass ? nlohmann::json(*r.pass) : nlohmann::json(); })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &PolarityResult::warnings)
      .verdict_is("pass")  // against `expected`: a reversed polarity fails the campaign
      .unit_of("sign", "1")
      .unit_of("output_positive_rate", "{output_unit}")
      .unit_of("output_negative_rate", "{output_unit}")
      .compute([](const ProcedureCall& call, const PolarityOptions& options) {
        const InputValue& positive = call.inputs.at("positive");
        const InputValue& negative = call.inputs.at("negative");
        return inertest::polarity(positive.value, negative.value, options, positive.standard_error,
                                  negative.standard_error);
      });
}

}  // namespace inertest
