// The web view's own HTML page (inertest serve): the instrument list. The campaign, history and
// fleet pages are the report's (report/report.h, report/archive_pages.h), rendered per request.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "inertest/report/report.h"

namespace inertest::serve {

// archive::instrument_list_json's object as one self-contained page: a table of the instruments
// (each linked to its history page, /instruments/ID, and its latest campaign's report,
// /campaigns/ID) with their latest verdicts, and a search box filtering the rows by id (inline
// script, no outside resource; ?q=TEXT fills it in). Links keep the page's language (?lang=zh).
std::string render_instrument_list_page(const nlohmann::json& instruments, report::Language language);

}  // namespace inertest::serve
