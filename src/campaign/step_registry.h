// The procedures a test plan can name. Each procedure registers a preparer under its plan kind
// (e.g. "scale_factor", "bias", "allan"): the preparer reads and checks its plan table (all
// validation happens here, before anything runs) and returns the action that computes the result.
// Registration is from the procedure's own step file (src/campaign/steps/<kind>_step.cc), so
// adding a procedure touches no shared file.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campaign/plan_table.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/progress.h"

namespace inertest::campaign {

struct Instrument {
  std::string id;
  std::string type = "gyro";       // "gyro" or "accelerometer"
  std::string output_unit = "1";   // the instrument's output unit, e.g. "pulse/s"
  std::optional<double> nominal_scale_factor;  // output unit per deg/s (per g for accelerometers)
  std::optional<double> sample_rate_hz;
  nlohmann::json to_json() const;
};

struct Site {
  std::string name;
  // Absent when the plan does not give it: a procedure whose figure depends on it asks for it (0
  // assumed unsaid gave Earth-rate inputs at the equator's, 1/cos(latitude) off).
  std::optional<double> latitude_deg;
  double gravity_m_s2 = 9.80665;
  double heading_deg = 0.0;  // azimuth of the instrument's IRA from north, for Earth-rate methods
  nlohmann::json to_json() const;
};

// The files a plan's steps write beside results.json (their exports), claimed as each step is
// read: a second step writing one of them, or a step writing results.json or report.html, would
// silently replace it, so it is an error in the plan.
class OutputClaims {
 public:
  // Why `path` (relative to the output directory) cannot be claimed at `where`, or nothing when it
  // is free (it is then claimed).
  std::optional<std::string> claim(const std::string& path, const SourceLocation& where);
  // The paths claimed (lexically normal), with where each is named.
  const std::map<std::string, SourceLocation>& claims() const { return claims_; }

 private:
  std::map<std::string, SourceLocation> claims_;  // by lexically normal path
};

struct PlanContext {
  Instrument instrument;
  Site site;
  // Filled while the steps are read (the preparers see the context const: it is the only part
  // they change).
  mutable OutputClaims outputs;
};

struct StepRunContext {
  ProgressCallback progress;
  std::string output_directory;  // where a plan's exports go: staged, moved beside results.json once every step has run
};

// Runs the procedure on data validated by the preparer; returns its result (to_json form).
using StepAction = std::function<nlohmann::json(const StepRunContext&)>;
// A step ready to run: its action, and the parameters it runs with by the spec's names (defaults and
// [instrument] values applied), of which its declared units are made (core/procedure_spec.h
// declared_unit); none for a step that is no declared procedure. Such a step declares the figures
// it reports instead, as a procedure's fields, so that its limits are checked before anything runs.
// A bound the step's own data states on one of its figures (a hand check's min and max): judged as
// a plan's limit, in the figure's unit, where the result gives the figure.
struct StatedLimit {
  std::string figure;
  std::optional<double> min;
  std::optional<double> max;
  SourceLocation where;
  bool yes_no = false;  // a pass/fail judged by eye: its figure 1 or 0, against min 1
};
struct PreparedAction {
  StepAction run;
  nlohmann::json parameters = nlohmann::json::object();
  std::vector<FieldSpec> figures = {};
  std::vector<StatedLimit> limits = {};
};
// Reads the step's keys (the campaign has already taken kind, name and limits), validates them and
// the data files, and returns the action. Must read every key it accepts: leftovers are errors.
using StepPreparer = std::function<PreparedAction(PlanTable& step, const PlanContext& context)>;

// The steps of the plan kinds that are not declared procedures, one file each in steps/; listed by
// step_registry.cc (no static initialiser of the shared library registers them).
PreparedAction prepare_hand_checks_step(PlanTable& step, const PlanContext& context);

// The step of a plan kind: a declared procedure's (procedure_step.h) or one of the above.
const StepPreparer* find_step(const std::string& kind);
std::vector<std::string> registered_step_kinds();

}  // namespace inertest::campaign
