// The CLI command of a declared procedure (core/procedure_spec.h), made from its spec.
#pragma once

#include "command.h"
#include "inertest/core/procedure_spec.h"

namespace inertest::cli {

// Adds `inertest <kind-in-kebab-case>` (or the last name of its command_path, to root being its group): a flag per parameter (--kebab-case, choices checked),
// --NAME-file / --NAME-output per input (exactly one of the two; a record's errors name the file),
// FILE..., --run NUMBER:FILE or a CSV listing per runs input (exactly one input of each group of
// alternatives), --column/--format for the records, and --json. Returns the action that runs the
// procedure and prints its JSON object or text report. `spec` must outlive the command (procedure_specs() does).
CommandAction add_procedure_command(CLI::App& root, const ProcedureSpec& spec);

}  // namespace inertest::cli
