// The plan step of a declared procedure (core/procedure_spec.h), made from its spec.
#pragma once

#include "campaign/step_registry.h"
#include "inertest/core/procedure_spec.h"

namespace inertest::campaign {

// Reads the step's keys: one per parameter (its name; a text parameter's choices checked; a
// parameter with an instrument default takes [instrument]'s value and is no key), NAME_file or
// NAME_output per input (exactly one), an array of files or [[procedure.run]] tables per runs
// input (their count checked), and format/column for the records. Returns the action
// that reads the records and runs the procedure, and its parameters. `spec` must outlive the action.
PreparedAction prepare_procedure_step(const ProcedureSpec& spec, PlanTable& step, const PlanContext& context);

}  // namespace inertest::campaign
