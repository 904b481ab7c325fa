// Options shared by the commands that read instrument-output records: --column and --format, and
// NUMBER:FILE runs.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "inertest/io/output_record.h"

namespace inertest::cli {

// Adds --column (text records) and --format (binary records) writing into source.
void add_record_options(CLI::App& command, OutputRecordSource& source);

// "NUMBER:FILE" -> (NUMBER, FILE), the file name may itself hold ':'. Throws Error naming the
// option and showing `example` when the text has another form.
std::pair<double, std::string> parse_number_and_file(const std::string& text, const std::string& option,
                                                     const std::string& example);

}  // namespace inertest::cli
