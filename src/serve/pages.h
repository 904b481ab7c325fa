// The web view's own HTML (inertest serve): the instrument list page, and what the server adds to the
// campaign, history and fleet pages, which are the report's (report/report.h,
// report/archive_pages.h) rendered per request.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/report/report.h"

namespace inertest::serve {

// archive::instrument_list_json's object as one self-contained page: a table of the instruments
// (each linked to its history page, /instruments/ID, and its latest campaign's report,
// /campaigns/ID) with their latest verdicts, and a search box filtering the rows by id (inline
// script, no outside resource; ?q=TEXT fills it in). Links keep the page's language (?lang=zh).
// With allow_add (the server's --allow-add), a form under the table sends a results.json file with
// the token the user types (POST /api/campaigns, Authorization: Bearer TOKEN) and shows the answer:
// the campaign added (linked to its report) or the error. Without it, no form.
std::string render_instrument_list_page(const nlohmann::json& instruments, report::Language language,
                                        bool allow_add);

// The page (a report, history or fleet page rendered with ReportOptions::embed_plot_data) with the
// interactive plots' script (plot_script.h) and style added before its </body>: zoom, pan, hover
// and downloads on every plot; the buttons and tooltips are hidden in print.
std::string with_interactive_plots(std::string page);

// The history page of instrument with a bar under its heading: a <select> of the instruments and
// one of the figures it has a history of (or all of them: figure empty), each going to the history
// chosen (/instruments/ID[?figure=P/F], in the page's language).
std::string with_history_switcher(std::string page, const std::vector<std::string>& instruments,
                                  const std::string& instrument, const std::vector<std::string>& figures,
                                  const std::string& figure, report::Language language);

}  // namespace inertest::serve
