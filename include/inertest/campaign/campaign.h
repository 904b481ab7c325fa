// A test campaign: a TOML test plan names the instrument, the site and the procedures with their
// data files, parameters and specification limits (IEEE Std 952-1997 specification format).
// run_campaign() validates the whole plan first (an error names the plan file and line, and
// nothing runs), then runs every procedure, checks the limits, and writes DIR/results.json.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/progress.h"

namespace inertest {

struct CampaignOptions {
  ProgressCallback progress;
};

struct CampaignSummary {
  nlohmann::json results;                 // what results.json holds
  std::vector<std::string> written_files; // paths written under the output directory
};

// Loads and validates the plan; throws Error naming the plan file and line on any problem.
// Returns the validated plan as JSON (instrument, site, procedures) without running anything.
nlohmann::json validate_plan(const std::string& plan_path);

// Every procedure kind a plan may name (sorted): the declared procedures and the hand-written steps.
std::vector<std::string> plan_kinds();

// Runs the plan and writes out_dir/results.json (created whole or not at all).
CampaignSummary run_campaign(const std::string& plan_path, const std::string& out_dir,
                             const CampaignOptions& options = {});

}  // namespace inertest
