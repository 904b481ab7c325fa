// A test campaign: a TOML test plan names the instrument, the site and the procedures with their
// data files, parameters and specification limits (IEEE Std 952-1997 specification format).
// run_campaign() validates the whole plan first (an error names the plan file and line, and
// nothing runs), then runs every procedure, checks the limits, and writes DIR/results.json.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/progress.h"

namespace inertest {

struct CampaignOptions {
  ProgressCallback progress;
  // The test report of the results, written beside results.json as report.html when given: made
  // before anything is written, so that a report that fails leaves no results without it.
  std::function<std::string(const nlohmann::json& results)> report_page;
};

struct CampaignSummary {
  nlohmann::json results;                 // what results.json holds
  std::vector<std::string> written_files; // paths written under the output directory, results.json first
  std::vector<std::string> removed_files; // what the last run of the campaign there wrote and this one did not
};

// Loads and validates the plan; throws Error naming the plan file and line on any problem.
// Returns the validated plan as JSON without running anything: instrument, site, and procedures
// (name, kind, and the parameters a declared procedure will run with, defaults applied).
nlohmann::json validate_plan(const std::string& plan_path);

// Every procedure kind a plan may name (sorted): the declared procedures and the hand-written steps.
std::vector<std::string> plan_kinds();

// Runs the plan and writes out_dir/results.json, the steps' exports and the report (all of them or,
// on an error, none; the output directory is left as it was). An out_dir holding another campaign's
// results.json (another instrument, plan title or date, or another plan file) is an error before
// anything runs; in one holding the same plan's, the files its last run wrote and this one does not
// are removed, unless edited since or read by the plan (out_dir/.inertest-written lists what a run
// wrote).
CampaignSummary run_campaign(const std::string& plan_path, const std::string& out_dir,
                             const CampaignOptions& options = {});

}  // namespace inertest
