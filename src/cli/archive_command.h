// `inertest archive SUBCOMMAND`: the archive's subcommands register themselves here, one file
// each (archive_add_command.cc, ...), as the top-level commands do with register_command.
#pragma once

#include <memory>
#include <string>

#include "command.h"
#include "inertest/archive/archive.h"

namespace inertest::cli {

// Registers `inertest archive NAME`; setup receives the `archive` subcommand to add itself to.
bool register_archive_command(const std::string& name, CommandSetup setup);

// Adds --db to command, writing into db.
void add_db_option(CLI::App& command, std::string& db);

// The archive that --db names, or the default one (default_archive_location) when empty.
std::string archive_location_option(const std::string& db);

// Opens the archive at archive_location_option(db); one that is not there is an Error unless
// `opening` is create (archive add, run --archive).
std::unique_ptr<archive::Archive> open_archive_option(const std::string& db,
                                                      archive::ArchiveOpening opening = archive::ArchiveOpening::existing);

}  // namespace inertest::cli
