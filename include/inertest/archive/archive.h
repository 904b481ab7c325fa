// The results archive: every campaign's results.json stored whole, plus one row per figure
// (campaign, procedure, figure, value, unit, uncertainty, verdict) for queries across days and
// across a fleet. One interface, two back-ends: SQLite (one file, WAL mode, the embedded default)
// and PostgreSQL (libpq; one server shared by a lab's test stations).
//
// The archive knows results, not procedures: a figure is any object {"value": number, "unit":
// string} inside a procedure's "result", named PROCEDURE/FIGURE as in results.json (the step's
// name, then the keys down to the figure, e.g. "scale_factor/scale_factor"). A figure the
// procedure could not compute ("value": null, e.g. a noise term the fit did not identify) is
// archived too, as not measured: its history shows that test, and the fleet does not take an older
// value for the instrument's latest.
//
// Contract: the schema is versioned and migrated on open; an add is one transaction (a process
// killed mid-add leaves the archive as it was); a campaign is identified by its content (the
// results JSON without its "processed_at" stamp), so adding it twice stores it once; several
// processes may add at once (SQLite: busy wait on the write lock; PostgreSQL: row locks and a
// unique key). Every query is parameterised.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"

namespace inertest::archive {

// The database itself failed (it cannot be opened, read or written: a file gone bad or unreadable,
// a lost connection, a full disk, a stored value that is not what the schema holds), as opposed to
// a question it answers with "not there" (an unknown instrument, figure or campaign: plain Error).
class DatabaseError : public Error {
 public:
  using Error::Error;
};

// The schema version this inertest writes and reads (migrations bring older archives up to it).
inline constexpr int schema_version = 4;

// One archived campaign, as `archive list` shows it.
struct CampaignEntry {
  std::string id;            // content hash (16 hex digits)
  std::string instrument;    // instrument.id
  std::string title;         // plan.title, "" when the plan has none
  std::string tested_on;     // when the test was done (results.json "tested_on")
  std::string processed_at;  // when it was processed, UTC ISO 8601
  std::string verdict;       // PASS, FAIL or NONE
  // The campaigns that processed records of this one again later: the figures they state again
  // replace this one's in histories and the fleet (Archive::add); its others stay. Empty for most.
  std::vector<std::string> superseded_by;
};

// One archived value of a figure.
struct FigurePoint {
  std::string tested_on;
  std::optional<double> value;        // none: not measured (the procedure ran and could not compute it)
  std::optional<double> uncertainty;  // 1 sigma, in the figure's unit
  std::string campaign;               // CampaignEntry::id
  std::string instrument;
};

// The values of one figure for one instrument, oldest test first.
struct FigureHistory {
  std::string instrument;
  std::string figure;  // PROCEDURE/FIGURE
  std::string unit;
  std::vector<FigurePoint> points;
  // Where a row of a table lies in it ("smoothing_s = 10" for "bias/bias_stability/1"), else none.
  std::optional<std::string> place;
  // The specification limits the campaigns' plans set on it (the latest test's), in unit. A plan's
  // max alone bounds the magnitude (|value| <= max, as the campaign judged it): lower_limit is then
  // -max and limit_on_magnitude is set.
  std::optional<double> lower_limit;
  std::optional<double> upper_limit;
  bool limit_on_magnitude = false;
  // {"instrument", "figure", "unit", "place", "points": [{"tested_on", "value", "uncertainty",
  // "campaign"}], "lower_limit", "upper_limit", "limit_on_magnitude"}; "value" is null where the
  // figure was not measured, "uncertainty", "place" and the limits where none is known.
  nlohmann::json to_json() const;
};

// The values of one figure across every instrument (optionally tested on or after a date),
// ordered by instrument then test date, with the specification limits the campaigns' plans set
// on it (the last campaign's, when they differ; a max alone is the spec |value| <= max, as in
// FigureHistory).
struct FleetFigure {
  std::string figure;
  std::string unit;
  std::vector<FigurePoint> points;
  std::optional<std::string> place;  // as FigureHistory's
  std::optional<double> lower_limit;
  std::optional<double> upper_limit;
  bool limit_on_magnitude = false;
};

// A figure archived in units that do not convert to one another (V/(deg/s) for analog gyros,
// pulse/s/(deg/s) for digital ones under one step name), or a row of a table archived at different
// places in it (a limit on "/bias_stability/1" in plans of other smoothing times: 10 s here, 100 s
// there): two quantities, which no history, control chart or capability may mix. The message names
// them and their instruments.
class NotOneQuantity : public Error {
 public:
  using Error::Error;
};

// What one add did.
struct AddOutcome {
  std::string id;
  std::string instrument;
  bool added = false;  // false: the same content was already archived
  // The campaigns whose earlier processing of the same records this one replaces (step by step),
  // and those whose later processing replaces steps of this one (an older results.json added after).
  std::vector<std::string> supersedes;
  std::vector<std::string> superseded_by;

  // {"id", "instrument", "file", "added", "supersedes", "superseded_by"}, as `archive add --json`,
  // `run --archive` and the web view's POST /api/campaigns answer; and the line `archive add` prints.
  nlohmann::json to_json(const std::string& file) const;
  std::string to_text(const std::string& file) const;
};

class Archive {
 public:
  virtual ~Archive() = default;

  // Adds a campaign's results (results.json parsed); source names the file in error messages.
  // Throws Error, changing nothing, when the results are malformed (a missing or mistyped key, a
  // results_schema_version this inertest does not know, a figure without a finite value or unit).
  // A step that read the same records (results.json "records", their SHA-256 in any order) as a step of
  // the same name of an earlier processing for the same instrument supersedes the figures of it
  // that it states again: those of the later processing are the ones histories, the fleet and
  // figures() show, and the earlier rows stay stored, marked (list() names who superseded them).
  // Later is processed_at, and of two processed in the same second the one added last. Results
  // without records (written before inertest named them) supersede nothing and are superseded by
  // nothing.
  virtual AddOutcome add(const nlohmann::json& results, const std::string& source) = 0;

  // Adds several campaigns (results, source) in one transaction: all are checked as add() checks
  // one, then all are stored, or (an Error, a failure of the database) none is.
  virtual std::vector<AddOutcome> add_all(const std::vector<std::pair<nlohmann::json, std::string>>& files) = 0;

  // Campaigns, oldest test first; only the instrument's when instrument is given.
  virtual std::vector<CampaignEntry> list(const std::optional<std::string>& instrument) = 0;

  // The archived values of figure (PROCEDURE/FIGURE) for instrument. Throws Error when the
  // instrument or the figure is not in the archive (the message lists the figures that are), and
  // NotOneQuantity when its units do not convert to one another.
  virtual FigureHistory history(const std::string& instrument, const std::string& figure) = 0;

  // The values of figure across the fleet, from tests on or after since (YYYY-MM-DD) when given.
  // Throws Error when no campaign archived the figure, and NotOneQuantity when its units do not
  // convert to one another.
  virtual FleetFigure fleet(const std::string& figure, const std::optional<std::string>& since) = 0;

  // The figures (PROCEDURE/FIGURE) archived, sorted; only those some plan set limits on when
  // with_limits_only.
  virtual std::vector<std::string> figures(bool with_limits_only) = 0;

  // The stored results JSON of a campaign, exactly as added. Throws Error for an unknown id.
  virtual nlohmann::json results(const std::string& id) = 0;

  // "sqlite" or "postgresql".
  virtual std::string backend() const = 0;
};

// The fleet's view of one figure (`inertest archive fleet --json`): each instrument's latest
// value (null when its latest test did not measure the figure), ordered by the instrument's first
// test (the order a batch came off the line),
// {"figure", "unit", "since", "lower_limit", "upper_limit", "limit_on_magnitude", "instruments": [{"instrument",
// "value", "uncertainty", "tested_on", "campaign", "tests"}], "control_chart": {"center", "ucl",
// "lcl", "moving_range_mean", "sigma", "out_of_control": [{"instrument", "value", "rule"}]} (over the
// measured latest values; null for fewer than 2), "capability": {"cp", "cpk"} (null where limits or spread lack;
// against [-max, max] when limit_on_magnitude)}.
// The chart and indices: numerics/control_chart.h.
nlohmann::json fleet_summary(const FleetFigure& fleet, const std::optional<std::string>& since);

// The campaigns as `inertest archive list --json` prints them: {"campaigns": [{"id", "instrument",
// "title", "tested_on", "processed_at", "verdict"}]}, in the order given.
nlohmann::json campaign_list_json(const std::vector<CampaignEntry>& campaigns);

// The instruments of campaigns (given oldest test first, as Archive::list returns them) as
// `inertest archive instruments --json` prints them: {"instruments": [{"instrument", "campaigns",
// "latest": {the latest campaign, as in campaign_list_json}}]}, sorted by instrument id.
nlohmann::json instrument_list_json(const std::vector<CampaignEntry>& campaigns);

// What the archive's report pages show (report/archive_pages.h): {"histories": [history_data of
// each instrument], "fleet": [fleet_summary of each figure], "not_comparable": [{"figure", "why"} of
// each figure archived across the fleet in units that do not convert (NotOneQuantity), left out of
// the fleet]}.
nlohmann::json report_data(Archive& archive, const std::vector<std::string>& figures);

// One instrument's history page: {"instrument", "figures": [FigureHistory::to_json() of each of
// figures its campaigns report], "not_comparable": [{"figure", "why"} of each its own campaigns
// archived in units that do not convert]}.
nlohmann::json history_data(Archive& archive, const std::string& instrument, const std::vector<std::string>& figures);

// report_data's "fleet" and "not_comparable" alone, of the tests on or after `since` (YYYY-MM-DD)
// when given, as `inertest archive fleet --since` counts them.
nlohmann::json fleet_data(Archive& archive, const std::vector<std::string>& figures,
                          const std::optional<std::string>& since);

// Whether location names a PostgreSQL server (a postgresql:// or postgres:// URL), not an SQLite file.
bool is_server_location(const std::string& location);

// Whether opening an archive may create it: a read of a mistyped path must not make an empty one.
enum class ArchiveOpening { create, existing };

// Opens (creating it when needed and allowed, and migrating its schema) the archive at location:
// a postgresql:// (or postgres://) URL, else a file path for SQLite. Throws Error when it cannot be
// opened, when a SQLite file is not there and `opening` is existing, or when its schema is newer
// than this inertest.
std::unique_ptr<Archive> open_archive(const std::string& location, ArchiveOpening opening = ArchiveOpening::create);

// Where the archive is when --db is not given: $INERTEST_DB, else ~/.local/share/inertest/archive.sqlite.
std::string default_archive_location();

// Checks results as add() does (throws the same Error) without touching any archive.
void check_results(const nlohmann::json& results, const std::string& source);

// Whether text is a test date as the archive stores and compares them: exactly YYYY-MM-DD, a day of
// the Gregorian calendar ("2026-02-30", "2026-04-04x" and a time after the day are not).
bool is_test_date(const std::string& text);

// Reads and parses a results.json; a syntax error names the file, line and column.
nlohmann::json read_results_file(const std::string& path);

}  // namespace inertest::archive
