// The archive, the same suite on both back-ends: SQLite in a scratch file, PostgreSQL on a server
// this test program starts itself (test_util/postgresql_server.h).
#include "inertest/archive/archive.h"

#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>

#include "archive/database.h"
#include "inertest/core/error.h"
#include "inertest/core/sha256.h"
#include "test_util/postgresql_server.h"
#include "test_util/demo_campaign.h"

namespace inertest::archive {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A results.json as inertest run writes it: one scale factor procedure with a limit, one bias.
nlohmann::json campaign(const std::string& instrument, const std::string& tested_on, double scale_factor,
                        double uncertainty = 0.02, const std::string& processed_at = "2026-01-01T00:00:00Z") {
  const bool pass = scale_factor <= 36001.0;
  return {
      {"results_schema_version", 1},
      {"inertest_version", "0.1.0"},
      {"tested_on", tested_on},
      {"processed_at", processed_at},
      {"plan", {{"title", "acceptance " + instrument}, {"operator", "Li Wei"}, {"station", "table 2"}}},
      {"instrument", {{"id", instrument}, {"type", "gyro"}}},
      {"site", nlohmann::json::object()},
      {"procedures",
       {{{"name", "scale_factor"},
         {"kind", "scale_factor"},
         {"result",
          {{"scale_factor", {{"value", scale_factor}, {"unit", "pulse/s/(deg/s)"}, {"uncertainty", uncertainty}}},
           {"nonlinearity", {{"value", 4.5}, {"unit", "ppm"}}},
           {"warnings", nlohmann::json::array()}}}},
        {{"name", "bias_static"},
         {"kind", "bias"},
         {"result", {{"bias", {{"value", 0.025}, {"unit", "deg/h"}}}, {"noise", {{"white", {{"value", 1e-3}, {"unit", "deg/h"}}}}}}}}}},
      {"verdicts",
       {{{"procedure", "scale_factor"}, {"figure", "scale_factor"}, {"value", scale_factor},
         {"unit", "pulse/s/(deg/s)"}, {"pass", pass}, {"min", 35999.0}, {"max", 36001.0}}}},
      {"verdict", pass ? "PASS" : "FAIL"},
  };
}

// The campaign with its scale factor (and the limit on it) in `unit`.
nlohmann::json campaign_in_unit(const std::string& instrument, const std::string& tested_on, double scale_factor,
                                const std::string& unit) {
  nlohmann::json results = campaign(instrument, tested_on, scale_factor);
  results["procedures"][0]["result"]["scale_factor"]["unit"] = unit;
  results["verdicts"][0]["unit"] = unit;
  return results;
}

class ArchiveBackend : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    if (std::string(GetParam()) == "postgresql") {
      auto& server = testing::PostgresqlServer::instance();
      // A failure, not a skip: `make test` installs PostgreSQL, and a suite that passed without it
      // would claim a back-end it never ran against.
      ASSERT_TRUE(server.available()) << server.why_unavailable();
      location_ = server.create_database();
    } else {
      location_ = scratch_.path() + "/archive.sqlite";
    }
  }
  std::unique_ptr<Archive> open() const { return open_archive(location_); }
  // Runs one SQL statement on the archive with the back-end's own client, behind inertest's back.
  void execute_sql(const std::string& sql) const {
    std::string command;
    if (std::string(GetParam()) == "postgresql") {
      command = fmt::format("/usr/lib/postgresql/15/bin/psql -q '{}' -c '{}' > /dev/null", location_, sql);
    } else {
      command = fmt::format("/usr/bin/python3 -c \"import sqlite3; c = sqlite3.connect('{}'); c.execute('{}'); "
                            "c.commit()\"",
                            location_, sql);
    }
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
  std::string error_of_add(Archive& archive, const nlohmann::json& results) const {
    try {
      archive.add(results, "bad/results.json");
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  }

  testing::ScratchDirectory scratch_;
  std::string location_;
};

TEST_P(ArchiveBackend, AddListHistoryGiveBackExactlyWhatWasStored) {
  auto archive = open();
  EXPECT_EQ(archive->backend(), GetParam());
  // Values that text round trips with too few digits would alter.
  const double k1 = 36000.23674828574, u1 = 0.027917825813075926, k2 = 36000.1 + 1e-10;
  const auto first = archive->add(campaign("FOG-0417", "2026-03-02", k2, u1), "b.json");
  const auto second = archive->add(campaign("FOG-0417", "2026-02-01", k1, u1), "a.json");
  archive->add(campaign("FOG-0418", "2026-02-15", 36000.5), "c.json");
  EXPECT_TRUE(first.added);
  EXPECT_EQ(first.instrument, "FOG-0417");
  EXPECT_EQ(first.id.size(), 16u);

  const auto all = archive->list(std::nullopt);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].id, second.id);  // oldest test first
  EXPECT_EQ(all[0].tested_on, "2026-02-01");
  EXPECT_EQ(all[0].title, "acceptance FOG-0417");
  EXPECT_EQ(all[0].processed_at, "2026-01-01T00:00:00Z");
  EXPECT_EQ(all[0].verdict, "PASS");
  EXPECT_EQ(all[1].instrument, "FOG-0418");
  EXPECT_EQ(archive->list(std::string("FOG-0417")).size(), 2u);
  EXPECT_TRUE(archive->list(std::string("FOG-9999")).empty());

  const FigureHistory history = archive->history("FOG-0417", "scale_factor/scale_factor");
  EXPECT_EQ(history.unit, "pulse/s/(deg/s)");
  ASSERT_EQ(history.points.size(), 2u);
  EXPECT_EQ(history.points[0].tested_on, "2026-02-01");
  EXPECT_EQ(history.points[0].value, k1);  // exactly: no digits lost
  EXPECT_EQ(history.points[0].uncertainty, u1);
  EXPECT_EQ(history.points[0].campaign, second.id);
  EXPECT_EQ(history.points[1].value, k2);
  EXPECT_EQ(history.lower_limit, 35999.0);  // the plans' limits on the figure
  EXPECT_EQ(history.upper_limit, 36001.0);
  EXPECT_EQ(archive->figures(true), std::vector<std::string>{"scale_factor/scale_factor"});
  EXPECT_EQ(archive->figures(false),
            (std::vector<std::string>{"bias_static/bias", "bias_static/noise/white", "scale_factor/nonlinearity",
                                      "scale_factor/scale_factor"}));
  // A nested figure is named by its path of keys; one without uncertainty has none.
  const auto nested = archive->history("FOG-0417", "bias_static/noise/white");
  ASSERT_EQ(nested.points.size(), 2u);
  EXPECT_EQ(nested.points[0].value, 1e-3);
  EXPECT_FALSE(nested.points[0].uncertainty);
  EXPECT_EQ(nested.to_json()["points"][0]["uncertainty"], nullptr);
  EXPECT_EQ(nested.to_json()["upper_limit"], nullptr);

  // The stored JSON is the file's, whole.
  EXPECT_EQ(archive->results(first.id), campaign("FOG-0417", "2026-03-02", k2, u1));
}

// A triad's figures ({"value": [x, y, z] or a 3x3, "unit", "uncertainty": the same shape}, issue 18)
// are stored element by element, each named by its place in "value".
TEST_P(ArchiveBackend, ArrayFiguresAreStoredElementByElement) {
  auto archive = open();
  nlohmann::json results = campaign("IMU-7", "2026-03-02", 36000.0);
  results["procedures"].push_back(
      {{"name", "imu"},
       {"kind", "imu_calibration"},
       {"result",
        {{"accelerometer",
          {{"bias", {{"value", {32864.0, 33275.0, 32364.0}}, {"unit", "count"}, {"uncertainty", {0.1, 0.2, 0.3}}}},
           {"misalignment", {{"value", {{0.0, 1e-3}, {0.0, 0.0}}}, {"unit", "rad"}}}}}}}});
  archive->add(results, "imu.json");
  const auto bias = archive->history("IMU-7", "imu/accelerometer/bias/value/1");
  ASSERT_EQ(bias.points.size(), 1u);
  EXPECT_EQ(bias.points[0].value, 33275.0);
  EXPECT_EQ(bias.points[0].uncertainty, 0.2);
  EXPECT_EQ(bias.unit, "count");
  const auto misalignment = archive->history("IMU-7", "imu/accelerometer/misalignment/value/0/1");
  ASSERT_EQ(misalignment.points.size(), 1u);
  EXPECT_EQ(misalignment.points[0].value, 1e-3);
  EXPECT_FALSE(misalignment.points[0].uncertainty);
}

// A limit on a row of a table (bias stability at the second smoothing time, named by the plan's JSON
// pointer) archives that row with its limit; the table's other rows and curves stay out.
TEST_P(ArchiveBackend, AFigureALimitNamesInAListIsArchivedWithItsLimit) {
  auto archive = open();
  nlohmann::json results = campaign("FOG-0417", "2026-03-02", 36000.0);
  nlohmann::json& bias = results["procedures"][1]["result"];
  bias["bias_stability"] = {{{"smoothing_s", 10.0}, {"value", 0.012}, {"unit", "deg/h"}},
                            {{"smoothing_s", 100.0}, {"value", 0.0057}, {"unit", "deg/h"}}};
  bias["normalised_stability_curve"] = {{{"tau_s", 0.01}, {"value", 1.5}, {"unit", "deg/h"}}};
  results["verdicts"].push_back({{"procedure", "bias_static"}, {"figure", "/bias_stability/1"}, {"value", 0.0057},
                                 {"pass", true}, {"max", 0.02 / 3600.0}, {"unit", "deg/s"}});
  results["verdicts"].push_back({{"procedure", "bias_static"}, {"figure", "/no_such/0"}, {"pass", true}, {"max", 1.0}});
  archive->add(results, "a.json");
  const auto stability = archive->history("FOG-0417", "bias_static/bias_stability/1");
  ASSERT_EQ(stability.points.size(), 1u);
  EXPECT_EQ(stability.points[0].value, 0.0057);
  EXPECT_EQ(stability.unit, "deg/h");
  ASSERT_TRUE(stability.upper_limit);
  EXPECT_NEAR(*stability.upper_limit, 0.02, 1e-15);  // the plan's limit, in the figure's unit
  EXPECT_TRUE(stability.limit_on_magnitude);  // a max alone: |value| <= 0.02
  EXPECT_EQ(stability.lower_limit, -*stability.upper_limit);
  EXPECT_EQ(stability.place, "smoothing_s = 100.0");  // where the row lies: the pages name it by it
  EXPECT_EQ(stability.to_json().at("place"), "smoothing_s = 100.0");
  EXPECT_FALSE(archive->history("FOG-0417", "scale_factor/scale_factor").place);
  EXPECT_EQ(archive->figures(true),
            (std::vector<std::string>{"bias_static/bias_stability/1", "scale_factor/scale_factor"}));
  const auto all = archive->figures(false);
  EXPECT_EQ(std::count(all.begin(), all.end(), "bias_static/bias_stability/0"), 0);
  EXPECT_EQ(std::count(all.begin(), all.end(), "bias_static/normalised_stability_curve/0"), 0);
}

// A figure the procedure could not compute ("value": null: a noise term the fit did not identify)
// is archived as not measured: the history shows that test, the fleet shows the instrument's latest
// test as not measured (not its older value) and charts the measured instruments only.
TEST_P(ArchiveBackend, AFigureNotMeasuredIsArchivedAsSuch) {
  auto archive = open();
  nlohmann::json later = campaign("FOG-N", "2026-02-01", 36000.0);
  later["procedures"][1]["result"]["noise"]["white"]["value"] = nullptr;
  archive->add(campaign("FOG-N", "2026-01-01", 36000.0), "a.json");
  archive->add(later, "b.json");
  archive->add(campaign("FOG-M", "2026-01-05", 36000.0), "c.json");
  const auto history = archive->history("FOG-N", "bias_static/noise/white");
  ASSERT_EQ(history.points.size(), 2u);
  EXPECT_EQ(history.points[0].value, 1e-3);
  EXPECT_FALSE(history.points[1].value);
  EXPECT_EQ(history.points[1].tested_on, "2026-02-01");
  EXPECT_EQ(history.to_json()["points"][1]["value"], nullptr);
  const auto text = testing::run_cli({"archive", "history", "FOG-N", "--figure", "bias_static/noise/white", "--db", location_});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("2026-02-01  not measured"));

  const auto fleet = fleet_summary(archive->fleet("bias_static/noise/white", std::nullopt), std::nullopt);
  ASSERT_EQ(fleet["instruments"].size(), 2u);
  EXPECT_EQ(fleet["instruments"][0]["instrument"], "FOG-N");  // first tested first
  EXPECT_EQ(fleet["instruments"][0]["value"], nullptr);  // not the 1e-3 of its first test
  EXPECT_EQ(fleet["instruments"][0]["tested_on"], "2026-02-01");
  EXPECT_EQ(fleet["instruments"][0]["tests"], 2);
  EXPECT_EQ(fleet["control_chart"], nullptr);  // one measured instrument: no moving range
  const auto fleet_text = testing::run_cli({"archive", "fleet", "--figure", "bias_static/noise/white", "--db", location_});
  ASSERT_EQ(fleet_text.exit_code, 0) << fleet_text.err;
  EXPECT_THAT(fleet_text.out, HasSubstr("FOG-N            2026-02-01 not measured"));

  // Repeatability (5.12.3 eq. (21)) is over the campaigns that measured the figure, 1e-3 and 3e-3
  // deg/h: Br = sqrt(2 · 1e-6 / 1) deg/h; the one that did not is said.
  const auto too_few = testing::run_cli({"archive", "repeatability", "FOG-N", "--figure", "bias_static/noise/white",
                                         "--db", location_});
  EXPECT_EQ(too_few.exit_code, 2);
  EXPECT_THAT(too_few.err, HasSubstr("figure 'bias_static/noise/white' of 'FOG-N': 1 of its 2 campaigns did not measure "
                                     "it, which leaves 1: repeatability needs at least 2"));
  nlohmann::json third = campaign("FOG-N", "2026-03-01", 36000.0);
  third["procedures"][1]["result"]["noise"]["white"]["value"] = 3e-3;
  archive->add(third, "d.json");
  const auto repeatability = testing::run_cli({"archive", "repeatability", "FOG-N", "--figure", "bias_static/noise/white",
                                               "--db", location_, "--json"});
  ASSERT_EQ(repeatability.exit_code, 0) << repeatability.err;
  const auto r = nlohmann::json::parse(repeatability.out);
  EXPECT_EQ(r["campaigns"].size(), 2u);
  EXPECT_EQ(r["not_measured"], nlohmann::json::array({history.points[1].campaign}));
  EXPECT_NEAR(r["result"]["bias_repeatability"]["value"].get<double>(), std::sqrt(2.0) * 1e-3, 1e-15);
  const auto said = testing::run_cli({"archive", "repeatability", "FOG-N", "--figure", "bias_static/noise/white", "--db", location_});
  EXPECT_THAT(said.out, HasSubstr("across 2 campaigns (1 more did not measure it)"));

  // Schema version 1 left such figures out (its table, as it made it: value NOT NULL): opening such
  // an archive rebuilds the table, fills them in from the stored results, and keeps the measured ones.
  execute_sql("CREATE TABLE figure_v1 (campaign TEXT NOT NULL REFERENCES campaign (id), procedure TEXT NOT NULL,"
              " figure TEXT NOT NULL, value DOUBLE PRECISION NOT NULL, unit TEXT NOT NULL, uncertainty DOUBLE PRECISION,"
              " verdict TEXT, lower_limit DOUBLE PRECISION, upper_limit DOUBLE PRECISION,"
              " PRIMARY KEY (campaign, procedure, figure))");
  execute_sql("INSERT INTO figure_v1 SELECT campaign, procedure, figure, value, unit, uncertainty, verdict, lower_limit,"
              " upper_limit FROM figure WHERE value IS NOT NULL");
  execute_sql("DROP TABLE figure");
  execute_sql("ALTER TABLE figure_v1 RENAME TO figure");
  execute_sql("CREATE INDEX figure_by_name ON figure (procedure, figure)");
  execute_sql("UPDATE schema_version SET version = 1");
  const auto migrated = open()->history("FOG-N", "bias_static/noise/white");
  ASSERT_EQ(migrated.points.size(), 3u);
  EXPECT_EQ(migrated.points[0].value, 1e-3);
  EXPECT_FALSE(migrated.points[1].value);
  EXPECT_EQ(open()->history("FOG-N", "scale_factor/scale_factor").points.size(), 3u);
}

// A limit on a row of a table ("/bias_stability/1") archives the row with where it lies in the
// table (smoothing_s = 10): in plans of other smoothing times the same row is another quantity,
// which history and repeatability do not mix (one record at 10 s and at 100 s gave a Br of
// 0.0047 deg/h).
TEST_P(ArchiveBackend, ARowOfATableIsOneQuantityAtOnePlaceInIt) {
  auto archive = open();
  const auto with_stability = [](const std::string& date, double smoothing_s, double value) {
    nlohmann::json results = campaign("FOG-R", date, 36000.0);
    results["procedures"][1]["result"]["bias_stability"] = nlohmann::json::array(
        {{{"smoothing_s", 1.0}, {"value", 0.05}, {"unit", "deg/h"}},
         {{"smoothing_s", smoothing_s}, {"value", value}, {"unit", "deg/h"}}});
    results["verdicts"].push_back({{"procedure", "bias_static"}, {"figure", "/bias_stability/1"}, {"value", value},
                                   {"unit", "deg/h"}, {"pass", true}, {"max", 0.05}});
    return results;
  };
  archive->add(with_stability("2026-03-01", 10.0, 0.012), "a");
  // A place written as a whole number (10 for 10.0, a file rewritten by jq) is the same place.
  nlohmann::json whole = with_stability("2026-03-02", 10.0, 0.013);
  whole["procedures"][1]["result"]["bias_stability"][1]["smoothing_s"] = 10;
  archive->add(whole, "b");
  // Not measured on a third day: its flag and reason are results, not where the row lies.
  nlohmann::json unmeasured = with_stability("2026-03-02", 10.0, 0.0);
  unmeasured["procedures"][1]["result"]["bias_stability"][1] = {
      {"smoothing_s", 10.0}, {"value", nullptr}, {"unit", "deg/h"}, {"measured", false}, {"reason", "too few windows"}};
  unmeasured["plan"]["title"] = "again";
  archive->add(unmeasured, "b2");
  EXPECT_EQ(archive->history("FOG-R", "bias_static/bias_stability/1").points.size(), 3u);
  archive->add(with_stability("2026-03-03", 100.0, 0.0057), "c");
  const std::string mixed = "figure 'bias_static/bias_stability/1' names rows at different places in their table: "
                            "smoothing_s = 10.0 (FOG-R 2026-03-01, FOG-R 2026-03-02); smoothing_s = 100.0 (FOG-R 2026-03-03)";
  try {
    archive->history("FOG-R", "bias_static/bias_stability/1");
    ADD_FAILURE() << "expected NotOneQuantity";
  } catch (const archive::NotOneQuantity& e) {
    EXPECT_THAT(e.message(), HasSubstr(mixed));
  }
  const auto repeatability = testing::run_cli(
      {"archive", "repeatability", "FOG-R", "--figure", "bias_static/bias_stability/1", "--db", location_});
  EXPECT_EQ(repeatability.exit_code, 2);
  EXPECT_THAT(repeatability.err, HasSubstr(mixed));
  // Schema version 2 stored no place (nor version 3's records): opening such an archive fills it in
  // from the stored results.
  execute_sql("DROP INDEX figure_by_records");
  for (const char* column : {"records", "superseded_by", "abscissa"}) execute_sql(fmt::format("ALTER TABLE figure DROP COLUMN {}", column));
  execute_sql("UPDATE schema_version SET version = 2");
  EXPECT_THROW(open()->history("FOG-R", "bias_static/bias_stability/1"), archive::NotOneQuantity);
  EXPECT_EQ(open()->history("FOG-R", "scale_factor/scale_factor").points.size(), 4u);
  // A row whose place is unknown (a campaign the migration could not read again) is not a conflict.
  execute_sql("UPDATE figure SET abscissa = NULL WHERE length(abscissa) = 19");  // smoothing_s = 100.0
  EXPECT_EQ(open()->history("FOG-R", "bias_static/bias_stability/1").points.size(), 4u);
}

TEST_P(ArchiveBackend, SameContentIsStoredOnce) {
  auto archive = open();
  const auto once = archive->add(campaign("FOG-0417", "2026-02-01", 36000.2), "a.json");
  const auto twice = archive->add(campaign("FOG-0417", "2026-02-01", 36000.2), "a.json");
  // Processed again later, the same content: still the same campaign.
  const auto reprocessed =
      archive->add(campaign("FOG-0417", "2026-02-01", 36000.2, 0.02, "2026-05-05T10:00:00Z"), "again.json");
  EXPECT_TRUE(once.added);
  EXPECT_FALSE(twice.added);
  EXPECT_FALSE(reprocessed.added);
  EXPECT_EQ(twice.id, once.id);
  EXPECT_EQ(reprocessed.id, once.id);
  EXPECT_EQ(archive->list(std::nullopt).size(), 1u);
  EXPECT_EQ(archive->history("FOG-0417", "scale_factor/scale_factor").points.size(), 1u);
  // Reopened (the migration runs again and finds nothing to do): the same content.
  EXPECT_EQ(open()->list(std::nullopt).size(), 1u);
  // Its numbers spelt otherwise (a whole number without ".0", as jq writes it): the same campaign,
  // not a second test of that day (it was stored twice).
  nlohmann::json respelt = campaign("FOG-0417", "2026-02-01", 36000.2);
  respelt["procedures"][0]["result"]["respelt"] = 108;
  nlohmann::json with_point_zero = respelt;
  with_point_zero["procedures"][0]["result"]["respelt"] = 108.0;
  const auto first = archive->add(with_point_zero, "b.json");
  const auto spelt = archive->add(respelt, "b_int.json");
  EXPECT_TRUE(first.added);
  EXPECT_FALSE(spelt.added);
  EXPECT_EQ(spelt.id, first.id);
  EXPECT_EQ(archive->list(std::nullopt).size(), 2u);
}

// The campaign as processed at processed_at from records: each step reads the record of its digest
// (sha256 of the text given).
nlohmann::json processed_from(const std::string& instrument, const std::string& tested_on, double scale_factor,
                              const std::string& processed_at, const std::string& scale_factor_record,
                              const std::string& bias_record) {
  nlohmann::json results = campaign(instrument, tested_on, scale_factor, 0.02, processed_at);
  results["procedures"][0]["records"] =
      nlohmann::json::array({{{"file", "k.csv"}, {"bytes", 5}, {"sha256", sha256_hex(scale_factor_record)}}});
  results["procedures"][1]["records"] =
      nlohmann::json::array({{{"file", "b.csv"}, {"bytes", 5}, {"sha256", sha256_hex(bias_record)}}});
  return results;
}

// Records processed again (a changed limit, a newer inertest, a plan without a date run another
// day) are one test: the later processing's figures replace the earlier's step by step, and the
// earlier stay stored and listed. The history counted such a test twice, and repeatability took
// Br = 0 from one test.
TEST_P(ArchiveBackend, ALaterProcessingOfTheSameRecordsSupersedesTheEarlier) {
  auto archive = open();
  const auto first = archive->add(processed_from("FOG-7", "2026-02-01", 36000.2, "2026-02-01T10:00:00Z", "K-1", "B-1"), "a");
  // Again a month later, without a plan date (tested_on the day processed); the bias from a new
  // record; without the nonlinearity (as a figure a limit no longer names).
  nlohmann::json processed_again = processed_from("FOG-7", "2026-03-01", 36000.4, "2026-03-01T09:00:00Z", "K-1", "B-2");
  processed_again["procedures"][0]["result"].erase("nonlinearity");
  const auto again = archive->add(processed_again, "b");
  EXPECT_TRUE(again.added);
  EXPECT_EQ(again.supersedes, std::vector<std::string>{first.id});
  EXPECT_TRUE(again.superseded_by.empty());
  const auto scale_factor = archive->history("FOG-7", "scale_factor/scale_factor");
  ASSERT_EQ(scale_factor.points.size(), 1u);
  EXPECT_EQ(scale_factor.points[0].value, 36000.4);
  EXPECT_EQ(scale_factor.points[0].campaign, again.id);
  EXPECT_EQ(archive->history("FOG-7", "bias_static/bias").points.size(), 2u);  // two records: two tests
  // A figure the later processing does not state again stays the earlier's (it was hidden).
  const auto nonlinearity = archive->history("FOG-7", "scale_factor/nonlinearity");
  ASSERT_EQ(nonlinearity.points.size(), 1u);
  EXPECT_EQ(nonlinearity.points[0].campaign, first.id);
  // An older processing added after: stored, each step superseded by the latest of its records
  // (the scale factor's by b, the bias's by a), and it changes no history.
  const auto older = archive->add(processed_from("FOG-7", "2026-01-15", 36000.1, "2026-01-15T08:00:00Z", "K-1", "B-1"), "c");
  EXPECT_TRUE(older.added);
  EXPECT_TRUE(older.supersedes.empty());
  std::vector<std::string> first_and_again = {first.id, again.id};
  std::sort(first_and_again.begin(), first_and_again.end());
  EXPECT_EQ(older.superseded_by, first_and_again);
  EXPECT_EQ(archive->history("FOG-7", "scale_factor/scale_factor").points.front().value, 36000.4);
  EXPECT_EQ(archive->history("FOG-7", "bias_static/bias").points.size(), 2u);
  // Another instrument's step of the same records (one record, several gyros' channels) is its own.
  archive->add(processed_from("FOG-8", "2026-03-02", 36000.9, "2026-03-02T09:00:00Z", "K-1", "B-1"), "d");
  EXPECT_EQ(archive->history("FOG-7", "scale_factor/scale_factor").points.size(), 1u);
  EXPECT_EQ(archive->fleet("scale_factor/scale_factor", std::nullopt).points.size(), 2u);
  // Processed in the same second: the one added last is the latest.
  const auto same_second = archive->add(processed_from("FOG-7", "2026-03-01", 36000.5, "2026-03-01T09:00:00Z", "K-1", "B-3"), "e");
  // It states the nonlinearity again too: the first's, current till now, is superseded as well.
  std::vector<std::string> again_and_first = {again.id, first.id};
  std::sort(again_and_first.begin(), again_and_first.end());
  EXPECT_EQ(same_second.supersedes, again_and_first);
  EXPECT_EQ(archive->history("FOG-7", "scale_factor/scale_factor").points.front().value, 36000.5);
  EXPECT_EQ(archive->history("FOG-7", "scale_factor/nonlinearity").points.front().campaign, same_second.id);
  // Every campaign stays listed, with the campaigns that superseded figures of it.
  const auto listed = open()->list(std::string("FOG-7"));
  ASSERT_EQ(listed.size(), 4u);
  const auto entry = [&](const std::string& id) {
    return *std::find_if(listed.begin(), listed.end(), [&](const CampaignEntry& e) { return e.id == id; });
  };
  std::vector<std::string> again_and_same_second = {again.id, same_second.id};
  std::sort(again_and_same_second.begin(), again_and_same_second.end());
  EXPECT_EQ(entry(first.id).superseded_by, again_and_same_second);
  EXPECT_EQ(entry(older.id).superseded_by, first_and_again);
  EXPECT_EQ(entry(again.id).superseded_by, std::vector<std::string>{same_second.id});
  EXPECT_TRUE(entry(same_second.id).superseded_by.empty());
  const auto text = testing::run_cli({"archive", "list", "--instrument", "FOG-7", "--db", location_});
  EXPECT_THAT(text.out, HasSubstr("(figures superseded by " + same_second.id + ")"));
  // Three bias records, three tests: B-1 (a's processing, the later of two), B-2 and B-3.
  EXPECT_EQ(archive->history("FOG-7", "bias_static/bias").points.size(), 3u);
  // A digest in capitals (as some tools print it) is the same digest.
  nlohmann::json capitals = processed_from("FOG-9", "2026-04-01", 36000.2, "2026-04-01T10:00:00Z", "K-1", "B-1");
  std::string upper = capitals["procedures"][0]["records"][0]["sha256"];
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  capitals["procedures"][0]["records"][0]["sha256"] = upper;
  archive->add(capitals, "f");
  const auto same_record = archive->add(processed_from("FOG-9", "2026-04-02", 36000.3, "2026-04-02T10:00:00Z", "K-1", "B-5"), "g");
  EXPECT_EQ(same_record.supersedes.size(), 1u);
  // Two runs listed the other way round are the same records: the later processing supersedes.
  nlohmann::json two_runs = processed_from("FOG-10", "2026-04-01", 36000.2, "2026-04-01T10:00:00Z", "K-1", "B-1");
  two_runs["procedures"][0]["records"].push_back({{"file", "k2.csv"}, {"bytes", 5}, {"sha256", sha256_hex("K-2")}});
  archive->add(two_runs, "h");
  nlohmann::json reordered = processed_from("FOG-10", "2026-04-01", 36000.3, "2026-04-02T10:00:00Z", "K-1", "B-1");
  reordered["procedures"][0]["records"] = nlohmann::json::array({two_runs["procedures"][0]["records"][1],
                                                                 two_runs["procedures"][0]["records"][0]});
  EXPECT_EQ(archive->add(reordered, "i").supersedes.size(), 1u);
  EXPECT_EQ(archive->history("FOG-10", "scale_factor/scale_factor").points.size(), 1u);
  // Results naming records without a digest are refused.
  nlohmann::json no_digest = processed_from("FOG-7", "2026-04-01", 36000.2, "2026-04-01T10:00:00Z", "K-9", "B-9");
  no_digest["procedures"][0]["records"][0].erase("sha256");
  EXPECT_THAT(error_of_add(*archive, no_digest), HasSubstr("each of \"records\" needs a \"sha256\" of 64 hex digits"));
}

TEST_P(ArchiveBackend, HostileResultsAreRefusedAndChangeNothing) {
  auto archive = open();
  archive->add(campaign("FOG-0417", "2026-02-01", 36000.2), "good.json");
  auto without = [](nlohmann::json j, const char* key) {
    j.erase(key);
    return j;
  };
  nlohmann::json wrong_schema = campaign("FOG-1", "2026-02-01", 1.0);
  wrong_schema["results_schema_version"] = 2;
  nlohmann::json string_value = campaign("FOG-1", "2026-02-01", 1.0);
  string_value["procedures"][1]["result"]["bias"]["value"] = "0.025";
  nlohmann::json bad_date = campaign("FOG-1", "2026-02-01", 1.0);
  bad_date["tested_on"] = "yesterday";
  nlohmann::json bad_verdict = campaign("FOG-1", "2026-02-01", 1.0);
  bad_verdict["verdict"] = "MAYBE";
  nlohmann::json slash_name = campaign("FOG-1", "2026-02-01", 1.0);
  slash_name["procedures"][0]["name"] = "a/b";
  nlohmann::json negative_uncertainty = campaign("FOG-1", "2026-02-01", 1.0, -5.0);
  nlohmann::json text_uncertainty = campaign("FOG-1", "2026-02-01", 1.0);
  text_uncertainty["procedures"][0]["result"]["scale_factor"]["uncertainty"] = "0.001";
  nlohmann::json swapped_limits = campaign("FOG-1", "2026-02-01", 1.0);
  swapped_limits["verdicts"][0]["min"] = 36001.0;
  swapped_limits["verdicts"][0]["max"] = 35999.0;
  nlohmann::json no_unit = campaign("FOG-1", "2026-02-01", 1.0);
  no_unit["procedures"][0]["result"]["scale_factor"].erase("unit");

  EXPECT_EQ(error_of_add(*archive, nlohmann::json::array()),
            "bad/results.json: not an inertest results file: expected a JSON object");
  EXPECT_EQ(error_of_add(*archive, without(campaign("FOG-1", "2026-02-01", 1.0), "instrument")),
            "bad/results.json: not an inertest results file: \"instrument\" is missing");
  EXPECT_EQ(error_of_add(*archive, without(campaign("FOG-1", "2026-02-01", 1.0), "procedures")),
            "bad/results.json: not an inertest results file: \"procedures\" is missing");
  EXPECT_EQ(error_of_add(*archive, wrong_schema),
            "bad/results.json: results_schema_version 2 is not one this inertest reads (1)");
  EXPECT_EQ(error_of_add(*archive, string_value),
            "bad/results.json: not an inertest results file: figure 'bias_static/bias': \"value\" is not a number");
  EXPECT_THAT(error_of_add(*archive, bad_date), HasSubstr("the test date 'yesterday' is not YYYY-MM-DD"));
  EXPECT_THAT(error_of_add(*archive, bad_verdict), HasSubstr("\"verdict\" must be PASS, FAIL or NONE, not 'MAYBE'"));
  EXPECT_THAT(error_of_add(*archive, slash_name), HasSubstr("procedure name 'a/b' is empty or contains '/'"));
  for (const auto* hostile : {&negative_uncertainty, &text_uncertainty}) {
    EXPECT_THAT(error_of_add(*archive, *hostile),
                HasSubstr("figure 'scale_factor/scale_factor': \"uncertainty\" is not a number of 0 or more"));
  }
  EXPECT_THAT(error_of_add(*archive, swapped_limits),
              HasSubstr("limit on 'scale_factor/scale_factor': min 36001 is above max 35999"));
  EXPECT_THAT(error_of_add(*archive, no_unit),
              HasSubstr("figure 'scale_factor/scale_factor': a limit names it, but it has no \"unit\""));

  ASSERT_EQ(archive->list(std::nullopt).size(), 1u);
  EXPECT_EQ(archive->list(std::nullopt)[0].instrument, "FOG-0417");
}

TEST_P(ArchiveBackend, UnknownNamesGiveClearErrors) {
  auto archive = open();
  archive->add(campaign("FOG-0417", "2026-02-01", 36000.2), "a.json");
  const auto error = [&](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error([&] { archive->history("FOG-9", "scale_factor/scale_factor"); }),
            "instrument 'FOG-9' has no campaign in the archive");
  EXPECT_EQ(error([&] { archive->history("FOG-0417", "scale_factor/bias"); }),
            "figure 'scale_factor/bias' is not archived for instrument 'FOG-0417' (archived: "
            "scale_factor/nonlinearity, scale_factor/scale_factor)");
  // An unknown procedure: every archived figure of the instrument is listed.
  EXPECT_EQ(error([&] { archive->history("FOG-0417", "bias/bias"); }),
            "figure 'bias/bias' is not archived for instrument 'FOG-0417' (archived: bias_static/bias, "
            "bias_static/noise/white, scale_factor/nonlinearity, scale_factor/scale_factor)");
  EXPECT_THAT(error([&] { archive->history("FOG-0417", "scale_factor"); }),
              HasSubstr("name it PROCEDURE/FIGURE as in results.json"));
  // Across the fleet too (it said only "is not archived").
  EXPECT_EQ(error([&] { archive->fleet("nope/nope", std::nullopt); }),
            "figure 'nope/nope' is not archived (archived: bias_static/bias, bias_static/noise/white, "
            "scale_factor/nonlinearity, scale_factor/scale_factor)");
  EXPECT_EQ(
      error([&] { archive->fleet("scale_factor/bias", std::nullopt); }),
      "figure 'scale_factor/bias' is not archived (archived: scale_factor/nonlinearity, scale_factor/scale_factor)");
  EXPECT_EQ(error([&] { archive->fleet("scale_factor/scale_factor", std::string("2099-01-01")); }),
            "figure 'scale_factor/scale_factor' has no test archived since 2099-01-01");
  EXPECT_EQ(error([&] { archive->fleet("scale_factor/scale_factor", std::string("2026-13")); }),
            "--since '2026-13': expected YYYY-MM-DD");
  for (const char* no_day : {"2026-13-45", "2026-02-30", "2025-02-29", "2026-04-04x", "2026-04-04T00:00:00Z"}) {
    EXPECT_EQ(error([&] { archive->fleet("scale_factor/scale_factor", std::string(no_day)); }),
              std::string("--since '") + no_day + "': expected YYYY-MM-DD");
  }
  EXPECT_EQ(error([&] { archive->results("0000000000000000"); }), "campaign '0000000000000000' is not in the archive");
}

TEST_P(ArchiveBackend, FleetCarriesEveryInstrumentAndTheLimits) {
  auto archive = open();
  archive->add(campaign("FOG-B", "2026-02-01", 36000.4), "1");
  archive->add(campaign("FOG-A", "2026-02-03", 36000.2), "2");
  archive->add(campaign("FOG-A", "2026-01-01", 36000.9), "3");
  const FleetFigure fleet = archive->fleet("scale_factor/scale_factor", std::nullopt);
  ASSERT_EQ(fleet.points.size(), 3u);
  EXPECT_EQ(fleet.points[0].instrument, "FOG-A");  // by instrument, then test date
  EXPECT_EQ(fleet.points[0].value, 36000.9);
  EXPECT_EQ(fleet.points[2].instrument, "FOG-B");
  EXPECT_EQ(fleet.lower_limit, 35999.0);
  EXPECT_EQ(fleet.upper_limit, 36001.0);
  EXPECT_EQ(archive->fleet("scale_factor/scale_factor", std::string("2026-02-01")).points.size(), 2u);
}

// The archive's schema is newer than this inertest: a clear error, and the archive untouched.
TEST_P(ArchiveBackend, NewerSchemaIsRefused) {
  open()->add(campaign("FOG-0417", "2026-02-01", 36000.2), "a.json");
  execute_sql("UPDATE schema_version SET version = 99");
  try {
    open();
    FAIL() << "opened an archive of schema version 99";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()),
                HasSubstr("the archive's schema version is 99, newer than this inertest knows (4): use a newer inertest"));
  }
}

// Several processes add at once: every campaign is there after. Each child process runs
// `inertest archive add` (run_cli) and reports its exit; all start before any is waited for.
TEST_P(ArchiveBackend, ConcurrentAddsFromSeveralProcessesLoseNothing) {
  constexpr int processes = 8;
  std::vector<std::string> files;
  for (int i = 0; i < processes; ++i) {
    files.push_back(scratch_.write(fmt::format("r{}.json", i),
                                   campaign(fmt::format("FOG-{:02}", i), "2026-02-01", 36000.0 + i).dump()));
  }
  // No open() before the race: the processes also race to create the schema (migrations are
  // serialised: SQLite's write lock, PostgreSQL's advisory lock).
  std::vector<pid_t> children;
  for (const auto& file : files) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      const auto run = testing::run_cli({"archive", "add", file, "--db", location_});
      if (run.exit_code != 0 || !run.err.empty()) std::fprintf(stderr, "%s", run.err.c_str());
      ::_exit(run.exit_code == 0 && run.err.empty() ? 0 : 1);
    }
    children.push_back(pid);
  }
  for (const pid_t pid : children) {
    int status = -1;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a station's add failed";
  }
  const auto all = open()->list(std::nullopt);
  ASSERT_EQ(all.size(), static_cast<std::size_t>(processes));
  for (int i = 0; i < processes; ++i) {
    EXPECT_EQ(open()->history(fmt::format("FOG-{:02}", i), "scale_factor/scale_factor").points.at(0).value,
              36000.0 + i);
  }
}

// A process killed (SIGKILL, no clean-up) in the middle of an add, after some of its figure rows
// are written: the archive is as it was, and the same campaign can be added afterwards.
TEST_P(ArchiveBackend, ProcessKilledMidAddLeavesTheArchiveAsItWas) {
  open()->add(campaign("FOG-0417", "2026-02-01", 36000.2), "a.json");
  const std::string file = scratch_.write("new.json", campaign("FOG-0418", "2026-02-02", 36000.3).dump());
  ::setenv("INERTEST_ARCHIVE_KILL_AFTER_FIGURES", "2", 1);
  const auto killed = testing::run_cli({"archive", "add", file, "--db", location_});
  ::unsetenv("INERTEST_ARCHIVE_KILL_AFTER_FIGURES");
  EXPECT_EQ(killed.exit_code, 128 + 9) << killed.err;
  auto archive = open();
  ASSERT_EQ(archive->list(std::nullopt).size(), 1u);
  EXPECT_THROW(archive->history("FOG-0418", "scale_factor/scale_factor"), Error);
  EXPECT_TRUE(archive->add(campaign("FOG-0418", "2026-02-02", 36000.3), "new.json").added);
  EXPECT_EQ(archive->history("FOG-0418", "scale_factor/nonlinearity").points.size(), 1u);
}

// The CLI: add (twice), list --json and history --json give back the stored figure exactly.
TEST_P(ArchiveBackend, CommandLineRoundTrip) {
  const nlohmann::json results = campaign("FOG-SIM-NAV", "2026-02-01", 36000.23674828574, 0.027917825813075926);
  const std::string file = scratch_.write("results.json", results.dump(2));
  const auto added = testing::run_cli({"archive", "add", file, "--db", location_, "--json"});
  ASSERT_EQ(added.exit_code, 0) << added.err;
  EXPECT_TRUE(nlohmann::json::parse(added.out)["added"][0]["added"].get<bool>());
  const auto again = testing::run_cli({"archive", "add", file, "--db", location_, "--json"});
  EXPECT_FALSE(nlohmann::json::parse(again.out)["added"][0]["added"].get<bool>());

  const auto list = testing::run_cli({"archive", "list", "--db", location_, "--json"});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  const auto campaigns = nlohmann::json::parse(list.out).at("campaigns");
  ASSERT_EQ(campaigns.size(), 1u);
  EXPECT_EQ(campaigns[0]["instrument"], "FOG-SIM-NAV");
  EXPECT_EQ(campaigns[0]["tested_on"], "2026-02-01");
  for (const char* key : {"id", "title", "processed_at", "verdict"}) EXPECT_TRUE(campaigns[0].contains(key)) << key;

  const auto history = testing::run_cli(
      {"archive", "history", "FOG-SIM-NAV", "--figure", "scale_factor/scale_factor", "--db", location_, "--json"});
  ASSERT_EQ(history.exit_code, 0) << history.err;
  const auto json = nlohmann::json::parse(history.out);
  EXPECT_EQ(json["instrument"], "FOG-SIM-NAV");
  EXPECT_EQ(json["figure"], "scale_factor/scale_factor");
  EXPECT_EQ(json["unit"], "pulse/s/(deg/s)");
  ASSERT_EQ(json["points"].size(), 1u);
  EXPECT_EQ(json["points"][0]["value"], results["procedures"][0]["result"]["scale_factor"]["value"]);
  EXPECT_EQ(json["points"][0]["uncertainty"], results["procedures"][0]["result"]["scale_factor"]["uncertainty"]);
  EXPECT_EQ(json["points"][0]["campaign"], campaigns[0]["id"]);
  const auto text = testing::run_cli(
      {"archive", "history", "FOG-SIM-NAV", "--figure", "scale_factor/scale_factor", "--db", location_});
  EXPECT_THAT(text.out, HasSubstr("\n  limits: min 35999, max 36001\n"));  // the plan's, in the figure's unit

  // A malformed file among good ones: nothing is added, the error names the file, line and column.
  const std::string good = scratch_.write("good.json", campaign("FOG-2", "2026-02-01", 1.0).dump());
  const std::string broken = scratch_.write("broken.json", "{\n  \"instrument\": {\"id\": \"X\"},\n  oops\n}\n");
  const auto refused = testing::run_cli({"archive", "add", good, broken, "--db", location_});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr(broken + ":3:3: not valid JSON"));
  const auto after = testing::run_cli({"archive", "list", "--db", location_, "--json"});
  EXPECT_EQ(nlohmann::json::parse(after.out).at("campaigns").size(), 1u);
  // A directory, and Python's json.dump of a NaN: said as what they are.
  const auto directory = testing::run_cli({"archive", "add", scratch_.path(), "--db", location_});
  EXPECT_EQ(directory.exit_code, 2);
  EXPECT_THAT(directory.err, HasSubstr(scratch_.path() + ": a directory, not a results.json"));
  const std::string nan = scratch_.write("nan.json", "{\"instrument\": {\"id\": \"X\", \"bias\": NaN}}\n");
  const auto not_a_number = testing::run_cli({"archive", "add", nan, "--db", location_});
  EXPECT_EQ(not_a_number.exit_code, 2);
  EXPECT_THAT(not_a_number.err, HasSubstr(nan + ":1:36: not valid JSON: syntax error while parsing value"));
  EXPECT_THAT(not_a_number.err, HasSubstr("(JSON has no NaN or Infinity: null stands for a missing number)"));
}

// Day-to-day repeatability of the archived campaigns. Scale factors 36000, 36001, 35999:
// K̄ = 36000, s = 1, Kr = 1/36000 = 27.78 ppm (GJB 2426A eq. 12). Biases 0.01, 0.02, 0.03 deg/h
// (in deg/s in the archive, converted): Br = 0.01 deg/h (eq. 21).
TEST_P(ArchiveBackend, RepeatabilityAcrossArchivedCampaigns) {
  auto archive = open();
  const double scale_factors[] = {36000.0, 36001.0, 35999.0};
  for (int i = 0; i < 3; ++i) {
    nlohmann::json results = campaign("FOG-0417", fmt::format("2026-02-0{}", i + 1), scale_factors[i]);
    results["procedures"][1]["result"]["bias"] = {{"value", 0.01 * (i + 1) / 3600.0}, {"unit", "deg/s"}};
    results["procedures"][0]["result"]["scale_factor_temperature_sensitivity"] = {{"value", 1.5 + i},
                                                                                 {"unit", "ppm/degC"}};
    archive->add(results, "r.json");
  }
  const auto scale = testing::run_cli({"archive", "repeatability", "FOG-0417", "--figure",
                                       "scale_factor/scale_factor", "--db", location_, "--json"});
  ASSERT_EQ(scale.exit_code, 0) << scale.err;
  const auto kr = nlohmann::json::parse(scale.out);
  EXPECT_EQ(kr["clause"], "GJB 2426A-2004 5.8.4, eq. (12)");
  EXPECT_EQ(kr["campaigns"].size(), 3u);
  EXPECT_NEAR_RELATIVE(kr["result"]["scale_factor_repeatability"]["value"].get<double>(), 1e6 / 36000.0, 1e-9);
  EXPECT_EQ(kr["result"]["scale_factor_repeatability"]["unit"], "ppm");

  const auto bias = testing::run_cli(
      {"archive", "repeatability", "FOG-0417", "--figure", "bias_static/bias", "--db", location_, "--json"});
  ASSERT_EQ(bias.exit_code, 0) << bias.err;
  const auto br = nlohmann::json::parse(bias.out);
  EXPECT_EQ(br["clause"], "GJB 2426A-2004 5.12.3, eq. (21)");
  EXPECT_NEAR_RELATIVE(br["result"]["bias_repeatability"]["value"].get<double>(), 0.01, 1e-9);

  const auto neither = testing::run_cli(
      {"archive", "repeatability", "FOG-0417", "--figure", "scale_factor/nonlinearity", "--db", location_});
  EXPECT_EQ(neither.exit_code, 2);
  EXPECT_THAT(neither.err, HasSubstr("repeatability is defined for a scale factor (GJB 2426A 5.8.4) or a bias"));
  // A scale factor of a dimensionless output (output_unit left "1") is one by its name.
  for (int i = 0; i < 3; ++i) {
    nlohmann::json results = campaign_in_unit("FOG-U", fmt::format("2026-02-0{}", i + 1), scale_factors[i], "1/(deg/s)");
    archive->add(results, "u.json");
  }
  const auto dimensionless = testing::run_cli(
      {"archive", "repeatability", "FOG-U", "--figure", "scale_factor/scale_factor", "--db", location_, "--json"});
  ASSERT_EQ(dimensionless.exit_code, 0) << dimensionless.err;
  EXPECT_NEAR_RELATIVE(nlohmann::json::parse(dimensionless.out)["result"]["scale_factor_repeatability"]["value"].get<double>(),
                       1e6 / 36000.0, 1e-9);
  // Named for the scale factor, but no output per input: no Kr of it (it gave 222.9 ppm).
  const auto sensitivity = testing::run_cli({"archive", "repeatability", "FOG-0417", "--figure",
                                             "scale_factor/scale_factor_temperature_sensitivity", "--db", location_});
  EXPECT_EQ(sensitivity.exit_code, 2);
  EXPECT_THAT(sensitivity.err, HasSubstr("(ppm/degC): repeatability is defined for a scale factor"));
}

// The fleet: each instrument's latest value in the order of first test; A = 36000.0,
// B = 36000.3, C = 36000.1 (C's earlier 36002 superseded). x̄ = 36000.1333, MR̄ = (0.3 + 0.2)/2,
// σ = MR̄/1.128379; limits [35999, 36001] from the plans: Cp = 2/6σ, Cpk = (36001 − x̄)/3σ.
TEST_P(ArchiveBackend, FleetControlChartAndCapability) {
  auto archive = open();
  archive->add(campaign("FOG-A", "2026-01-01", 36000.0), "a");
  archive->add(campaign("FOG-B", "2026-01-02", 36000.3), "b");
  archive->add(campaign("FOG-C", "2026-01-03", 36002.0), "c1");
  archive->add(campaign("FOG-C", "2026-01-09", 36000.1), "c2");
  const auto run = testing::run_cli({"archive", "fleet", "--figure", "scale_factor/scale_factor", "--db", location_, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto fleet = nlohmann::json::parse(run.out);
  ASSERT_EQ(fleet["instruments"].size(), 3u);
  EXPECT_EQ(fleet["instruments"][2]["instrument"], "FOG-C");
  EXPECT_EQ(fleet["instruments"][2]["value"], 36000.1);
  EXPECT_EQ(fleet["instruments"][2]["tests"], 2);
  const double center = (36000.0 + 36000.3 + 36000.1) / 3.0;
  const double sigma = ((0.3 + 0.2) / 2.0) / 1.1283791670955126;
  EXPECT_NEAR(fleet["control_chart"]["center"].get<double>(), center, 1e-9);
  EXPECT_NEAR(fleet["control_chart"]["ucl"].get<double>(), center + 3 * sigma, 1e-9);
  EXPECT_NEAR(fleet["control_chart"]["lcl"].get<double>(), center - 3 * sigma, 1e-9);
  EXPECT_TRUE(fleet["control_chart"]["out_of_control"].empty());
  EXPECT_NEAR(fleet["capability"]["cp"].get<double>(), 2.0 / (6 * sigma), 1e-6);
  EXPECT_NEAR(fleet["capability"]["cpk"].get<double>(), (36001.0 - center) / (3 * sigma), 1e-6);
  // Since 2026-01-02: A drops out, C's earlier test too.
  const auto since = testing::run_cli({"archive", "fleet", "--figure", "scale_factor/scale_factor", "--since",
                                       "2026-01-02", "--db", location_, "--json"});
  EXPECT_EQ(nlohmann::json::parse(since.out)["instruments"].size(), 2u);
}

// inertest run --archive DB: the campaign's results go straight into the archive.
TEST_P(ArchiveBackend, RunAddsItsResultsToTheArchive) {
  const auto run = testing::run_cli({"run", testing::source_path("examples/scale_factor/plan.toml"), "--out",
                                     scratch_.path() + "/out", "--archive", location_});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto written = read_results_file(scratch_.path() + "/out/results.json");
  const auto campaigns = open()->list(std::nullopt);
  ASSERT_EQ(campaigns.size(), 1u);
  EXPECT_EQ(campaigns[0].instrument, written["instrument"]["id"]);
  EXPECT_EQ(campaigns[0].processed_at, written["processed_at"]);
  EXPECT_EQ(open()->results(campaigns[0].id), written);
}

// results.json names each record a step read, from the plan's directory, with its size and SHA-256
// (what `sha256sum` prints); the same plan run again with a changed limit supersedes its figures.
TEST_P(ArchiveBackend, ARunAgainWithAChangedLimitSupersedesTheFirst) {
  const std::string points = testing::read_file(testing::source_path("examples/scale_factor/points.csv"));
  scratch_.write("data/points.csv", points);
  const auto plan = [&](int limit) {
    return scratch_.write("plan.toml", fmt::format("[instrument]\nid = \"FOG-1\"\noutput_unit = \"pulse/s\"\n\n"
                                                   "[[procedure]]\nkind = \"scale_factor\"\nfile = \"data/points.csv\"\n"
                                                   "[procedure.limits]\nnonlinearity = {{ max = {}, unit = \"ppm\" }}\n",
                                                   limit));
  };
  const auto first = testing::run_cli({"run", plan(100), "--out", scratch_.path() + "/out", "--archive", location_});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto written = read_results_file(scratch_.path() + "/out/results.json");
  EXPECT_EQ(written["procedures"][0]["records"],
            nlohmann::json::array({{{"file", "data/points.csv"}, {"bytes", points.size()}, {"sha256", sha256_hex(points)}}}));
  const auto second = testing::run_cli({"run", plan(50), "--out", scratch_.path() + "/out", "--archive", location_});
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.err, HasSubstr("(an earlier processing of the same records)"));
  const auto history = open()->history("FOG-1", "scale_factor/nonlinearity");
  ASSERT_EQ(history.points.size(), 1u);
  EXPECT_EQ(history.upper_limit, 50.0);
  EXPECT_EQ(open()->list(std::nullopt).size(), 2u);
}

// A plan that is refused makes no archive (a mistyped key left a new, empty one behind).
TEST(ArchiveRun, ARefusedPlanMakesNoArchive) {
  testing::ScratchDirectory scratch;
  const std::string plan = scratch.write("plan.toml", "[plan]\ntitel = \"typo\"\n");
  const std::string location = scratch.path() + "/new/archive.sqlite";
  const auto run = testing::run_cli({"run", plan, "--out", scratch.path() + "/out", "--archive", location});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("plan.toml:2:1"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(location));
  EXPECT_FALSE(std::filesystem::exists(scratch.path() + "/new"));
  // Nor does a valid plan whose data is bad (the archive was made before the data was read).
  scratch.write("points.csv", "rate,output\n0,1\n5,x\n");
  const std::string bad_data = scratch.write("data.toml", "[instrument]\nid = \"FOG-1\"\noutput_unit = \"pulse/s\"\n\n"
                                                         "[[procedure]]\nkind = \"scale_factor\"\nfile = \"points.csv\"\n");
  const auto bad = testing::run_cli({"run", bad_data, "--out", scratch.path() + "/out", "--archive", location});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("points.csv:3:3"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(scratch.path() + "/new"));
  // An archive that was there stays, with what it held.
  const auto good = testing::run_cli({"run", testing::source_path("examples/scale_factor/plan.toml"), "--out",
                                      scratch.path() + "/good", "--archive", location});
  ASSERT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(testing::run_cli({"run", bad_data, "--out", scratch.path() + "/out", "--archive", location}).exit_code, 2);
  EXPECT_EQ(archive::open_archive(location, archive::ArchiveOpening::existing)->list(std::nullopt).size(), 1u);
}

// An analog gyro's K in V/(deg/s) and a digital one's in pulse/s/(deg/s) under one step name are
// two quantities: history and fleet say so, naming the units and their instruments (a fleet failed
// with "cannot convert"); the report names the figure on the fleet page and writes every other page.
TEST_P(ArchiveBackend, AFigureOfTwoQuantitiesIsNamedNotMixed) {
  auto archive = open();
  archive->add(campaign("FOG-D1", "2026-01-01", 36000.0), "d1");
  archive->add(campaign_in_unit("FOG-A1", "2026-01-02", 36000.3, "V/(deg/s)"), "a1");
  // A unit that converts to another is of its quantity, and said with it (the message listed it as
  // not converting).
  archive->add(campaign_in_unit("FOG-D2", "2026-01-03", 36.0001, "pulse/ms/(deg/s)"), "d2");
  try {
    archive->fleet("scale_factor/scale_factor", std::nullopt);
    ADD_FAILURE() << "expected NotOneQuantity";
  } catch (const archive::NotOneQuantity& e) {
    EXPECT_THAT(e.message(), HasSubstr("figure 'scale_factor/scale_factor' is archived in units that do not convert to "
                                       "one another: [V/(deg/s) (FOG-A1 2026-01-02)] and [pulse/ms/(deg/s) "
                                       "(FOG-D2 2026-01-03); pulse/s/(deg/s) (FOG-D1 2026-01-01)]"));
  }
  EXPECT_EQ(archive->fleet("scale_factor/nonlinearity", std::nullopt).points.size(), 3u);  // ppm for all
  EXPECT_EQ(archive->history("FOG-A1", "scale_factor/scale_factor").unit, "V/(deg/s)");  // one instrument, one unit
  const auto report = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/pages", "--figure",
                                        "scale_factor/scale_factor", "--figure", "scale_factor/nonlinearity",
                                        "--db", location_});
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const std::string fleet = testing::read_file(scratch_.path() + "/pages/fleet.html");
  EXPECT_THAT(fleet, HasSubstr("Not comparable: archived in units that do not convert"));
  EXPECT_THAT(fleet, HasSubstr("[V/(deg/s) (FOG-A1 2026-01-02)]"));
  // Each instrument's own history is one quantity, and shown.
  const std::string history = testing::read_file(scratch_.path() + "/pages/history-FOG-A1.html");
  EXPECT_THAT(history, HasSubstr("scale_factor/nonlinearity"));
  EXPECT_THAT(history, HasSubstr("V/(deg/s)"));
  const auto fleet_command = testing::run_cli({"archive", "fleet", "--figure", "scale_factor/scale_factor", "--db", location_});
  EXPECT_EQ(fleet_command.exit_code, 2);
  EXPECT_THAT(fleet_command.err, HasSubstr("cannot be charted as one figure"));
  // One dimension is not enough: bare temperatures in degC and K do not convert (history, fleet and
  // the report failed on "cannot convert the temperature").
  nlohmann::json celsius = campaign("FOG-T1", "2026-01-03", 36000.0);
  celsius["procedures"][0]["result"]["worst_temperature"] = {{"value", 60.0}, {"unit", "degC"}};
  nlohmann::json kelvin = campaign("FOG-T2", "2026-01-04", 36000.0);
  kelvin["procedures"][0]["result"]["worst_temperature"] = {{"value", 333.15}, {"unit", "K"}};
  archive->add(celsius, "t1");
  archive->add(kelvin, "t2");
  EXPECT_THAT([&] { archive->fleet("scale_factor/worst_temperature", std::nullopt); },
              ::testing::ThrowsMessage<archive::NotOneQuantity>(HasSubstr("[degC (FOG-T1 2026-01-03)] and [K (FOG-T2 2026-01-04)]")));
}

// The fleet since a date leaves out a figure no test since then reports (the web view's /fleet?since=
// was a 404 for it).
TEST_P(ArchiveBackend, TheFleetSinceADateLeavesOutFiguresNotTestedSince) {
  auto archive = open();
  nlohmann::json old = campaign("FOG-O1", "2026-01-01", 36000.0);
  old["procedures"][0]["result"]["output_at_rest"] = {{"value", 1.5}, {"unit", "pulse/s"}};
  archive->add(old, "o1");
  archive->add(campaign("FOG-O1", "2026-03-01", 36000.1), "o2");
  const std::vector<std::string> figures = {"scale_factor/scale_factor", "scale_factor/output_at_rest"};
  EXPECT_EQ(archive::fleet_data(*archive, figures, std::nullopt).at("fleet").size(), 2u);
  const nlohmann::json since = archive::fleet_data(*archive, figures, "2026-02-01");
  ASSERT_EQ(since.at("fleet").size(), 1u);
  EXPECT_EQ(since.at("fleet")[0].at("figure"), "scale_factor/scale_factor");
  EXPECT_EQ(since.at("fleet")[0].at("since"), "2026-02-01");
}

// An instrument whose own campaigns archived a figure in units that do not convert: its history page
// says so (the figure was left out of it with no word).
TEST_P(ArchiveBackend, AHistoryOfTwoQuantitiesIsNamedOnItsPage) {
  auto archive = open();
  archive->add(campaign("FOG-M1", "2026-01-01", 36000.0), "m1");
  archive->add(campaign_in_unit("FOG-M1", "2026-01-02", 36000.3, "V/(deg/s)"), "m2");
  for (const char* day : {"2026-01-03", "2026-01-04", "2026-01-05"}) {
    archive->add(campaign("FOG-M1", day, 36000.0), std::string("m-") + day);
  }
  const nlohmann::json data = archive::history_data(*archive, "FOG-M1", {"scale_factor/scale_factor"});
  EXPECT_TRUE(data.at("figures").empty());
  ASSERT_EQ(data.at("not_comparable").size(), 1u);
  EXPECT_EQ(data.at("not_comparable")[0].at("figure"), "scale_factor/scale_factor");
  const auto report = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/pages", "--figure",
                                        "scale_factor/scale_factor", "--db", location_});
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const std::string history = testing::read_file(scratch_.path() + "/pages/history-FOG-M1.html");
  EXPECT_THAT(history, HasSubstr("<section class=\"not-comparable\"><h2>Not comparable: archived in units that do "
                                 "not convert</h2>"));
  // The first three tests of each unit, and a count of the others.
  EXPECT_THAT(history, HasSubstr("[pulse/s/(deg/s) (FOG-M1 2026-01-01, FOG-M1 2026-01-03, FOG-M1 2026-01-04, 1 more)] "
                                 "and [V/(deg/s) (FOG-M1 2026-01-02)]"));
  // Printed, its figures are kept whole rather than each put on a page of its own.
  EXPECT_THAT(history, HasSubstr("<body class=\"archive\">"));
  EXPECT_THAT(history, HasSubstr("body.archive section.procedure { break-before: auto; break-inside: avoid; }"));
}

// inertest archive report: the fleet page and one history page per instrument; by default the
// figures some plan set limits on; an unknown figure is an error that writes nothing.
TEST_P(ArchiveBackend, ReportWritesTheFleetAndHistoryPages) {
  auto archive = open();
  archive->add(campaign("FOG-A", "2026-01-01", 36000.0), "a");
  archive->add(campaign("FOG-B", "2026-01-02", 36000.3), "b");
  const auto run = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/pages", "--db", location_, "--lang", "zh"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* page : {"fleet.html", "history-FOG-A.html", "history-FOG-B.html"}) {
    EXPECT_TRUE(std::filesystem::exists(scratch_.path() + "/pages/" + page)) << page;
  }
  std::ifstream fleet(scratch_.path() + "/pages/fleet.html");
  const std::string text{std::istreambuf_iterator<char>(fleet), {}};
  EXPECT_THAT(text, HasSubstr("scale_factor/scale_factor"));
  EXPECT_THAT(text, Not(HasSubstr("scale_factor/nonlinearity")));  // no limits on it
  const auto unknown = testing::run_cli(
      {"archive", "report", "--out", scratch_.path() + "/none", "--figure", "x/y", "--db", location_});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("figure 'x/y' is not archived"));
  EXPECT_FALSE(std::filesystem::exists(scratch_.path() + "/none"));

  // An id with a '/' (a lab's LAB2/FOG-001) or a '%' names a file of its own in the directory.
  archive->add(campaign("LAB2/FOG-001", "2026-01-03", 36000.1), "c");
  archive->add(campaign("50%", "2026-01-04", 36000.2), "d");
  const auto slash = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/slash", "--db", location_});
  ASSERT_EQ(slash.exit_code, 0) << slash.err;
  for (const char* page : {"fleet.html", "history-FOG-A.html", "history-LAB2%2FFOG-001.html", "history-50%25.html"}) {
    EXPECT_TRUE(std::filesystem::exists(scratch_.path() + "/slash/" + page)) << page;
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(scratch_.path() + "/slash"),
                          std::filesystem::directory_iterator()),
            5);  // the pages and nothing else (no staging left)

  // A directory where a page goes: an error naming it, the pages as they were and no staging left
  // (fleet.html was replaced, then an internal error, exit 3, left the staging directory behind).
  std::filesystem::create_directories(scratch_.path() + "/blocked/history-FOG-A.html");
  const auto blocked = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/blocked", "--db", location_});
  EXPECT_EQ(blocked.exit_code, 2);
  EXPECT_THAT(blocked.err, HasSubstr("/blocked/history-FOG-A.html: a directory is where a file is to be written"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(scratch_.path() + "/blocked"),
                          std::filesystem::directory_iterator()),
            1);
  const auto file = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/slash/fleet.html", "--db", location_});
  EXPECT_EQ(file.exit_code, 2);
  EXPECT_THAT(file.err, HasSubstr("fleet.html: the output directory is a file"));
  // A directory under a file cannot be made: an error at the path the system names (it was an
  // internal error, exit 3).
  const auto under = testing::run_cli({"archive", "report", "--out", scratch_.path() + "/slash/fleet.html/pages", "--db", location_});
  EXPECT_EQ(under.exit_code, 2);
  EXPECT_THAT(under.err, HasSubstr("inertest: error: " + scratch_.path() + "/slash/fleet.html/pages: Not a directory"));
}

// The demo's results.json (inertest demo).
std::string demo_results() { return testing::demo_campaign_directory() + "/results.json"; }

// The issue's acceptance: the demo's results added twice, then list and history give back exactly
// the scale factor stored in results.json, as one campaign.
TEST_P(ArchiveBackend, DemoResultsRoundTripExactly) {
  for (int i = 0; i < 2; ++i) {
    const auto added = testing::run_cli({"archive", "add", demo_results(), "--db", location_, "--json"});
    ASSERT_EQ(added.exit_code, 0) << added.err;
  }
  const auto list = testing::run_cli({"archive", "list", "--db", location_, "--json"});
  const auto campaigns = nlohmann::json::parse(list.out).at("campaigns");
  ASSERT_EQ(campaigns.size(), 1u);
  EXPECT_EQ(campaigns[0]["instrument"], "FOG-SIM-NAV");
  const auto history = testing::run_cli(
      {"archive", "history", "FOG-SIM-NAV", "--figure", "scale_factor/scale_factor", "--db", location_, "--json"});
  ASSERT_EQ(history.exit_code, 0) << history.err;
  const auto points = nlohmann::json::parse(history.out).at("points");
  ASSERT_EQ(points.size(), 1u);
  const nlohmann::json results = read_results_file(demo_results());
  int found = 0;
  for (const auto& procedure : results.at("procedures")) {
    if (procedure.at("name") != "scale_factor") continue;
    ++found;
    EXPECT_EQ(points[0]["value"], procedure.at("result").at("scale_factor").at("value"));
    EXPECT_EQ(points[0]["uncertainty"], procedure.at("result").at("scale_factor").at("uncertainty"));
  }
  EXPECT_EQ(found, 1);
  EXPECT_EQ(points[0]["campaign"], campaigns[0]["id"]);
}

// A plan's max alone bounds the magnitude (campaign.cc judges |value| <= max): the history and the
// fleet take the spec as [-max, max] and say so. Biases -0.04, -0.06, -0.05 deg/h under max 0.05:
// x̄ = -0.05, MR̄ = (0.02 + 0.01)/2, σ = MR̄/1.128379; Cp = 0.1/6σ, Cpk = min(0.05 - x̄, x̄ + 0.05)/3σ
// = 0 (against the max alone, one-sided, it read Cp null and Cpk 2.51).
TEST_P(ArchiveBackend, AMaxAloneIsALimitOnTheMagnitude) {
  auto archive = open();
  const double biases[] = {-0.04, -0.06, -0.05};
  for (int i = 0; i < 3; ++i) {
    nlohmann::json results = campaign(fmt::format("FOG-{}", i), "2026-02-01", 36000.0);
    results["procedures"][1]["result"]["bias"]["value"] = biases[i];
    results["verdicts"].push_back({{"procedure", "bias_static"}, {"figure", "bias"}, {"value", biases[i]},
                                   {"unit", "deg/h"}, {"pass", std::abs(biases[i]) <= 0.05}, {"max", 0.05}});
    archive->add(results, "r.json");
  }
  const FigureHistory history = archive->history("FOG-1", "bias_static/bias");
  EXPECT_EQ(history.lower_limit, -0.05);
  EXPECT_EQ(history.upper_limit, 0.05);
  EXPECT_TRUE(history.limit_on_magnitude);
  EXPECT_EQ(history.to_json()["limit_on_magnitude"], true);
  EXPECT_EQ(history.to_json()["lower_limit"], -0.05);
  // min with max: the signed value, as before.
  EXPECT_FALSE(archive->history("FOG-1", "scale_factor/scale_factor").limit_on_magnitude);
  EXPECT_EQ(archive->history("FOG-1", "scale_factor/scale_factor").to_json()["limit_on_magnitude"], false);

  const auto run = testing::run_cli({"archive", "fleet", "--figure", "bias_static/bias", "--db", location_, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto fleet = nlohmann::json::parse(run.out);
  EXPECT_EQ(fleet["limit_on_magnitude"], true);
  EXPECT_EQ(fleet["lower_limit"], -0.05);
  const double sigma = ((0.02 + 0.01) / 2.0) / 1.1283791670955126;
  ASSERT_TRUE(fleet["capability"]["cp"].is_number());
  EXPECT_NEAR(fleet["capability"]["cp"].get<double>(), 0.1 / (6 * sigma), 1e-9);
  EXPECT_NEAR(fleet["capability"]["cpk"].get<double>(), 0.0, 1e-9);
  const auto text = testing::run_cli({"archive", "history", "FOG-1", "--figure", "bias_static/bias", "--db", location_});
  EXPECT_THAT(text.out, HasSubstr("\n  limits: |value| <= 0.05\n"));
}

// A verdict's limit that is no number ("max": "inf", written by hand) was dropped: the history showed
// the figure with no limit at all.
TEST_P(ArchiveBackend, AVerdictsLimitMustBeANumber) {
  nlohmann::json text_limit = campaign("FOG-2", "2026-02-01", 36000.0);
  text_limit["verdicts"][0]["max"] = "inf";
  auto archive = open();
  EXPECT_EQ(error_of_add(*archive, text_limit),
            "bad/results.json: not an inertest results file: limit on 'scale_factor/scale_factor': \"max\" must be a "
            "number");
  EXPECT_TRUE(archive->list(std::nullopt).empty());
}

// Two steps of one name (a plan's two scale factor steps) give the same figure twice: the file is
// refused by name, and a multi-file add that holds it adds nothing, the good files before it neither.
TEST_P(ArchiveBackend, AFigureTwiceIsRefusedAndAMultiFileAddIsAllOrNothing) {
  nlohmann::json twice = campaign("FOG-2", "2026-02-01", 36000.0);
  twice["procedures"].push_back(twice["procedures"][0]);
  twice["procedures"][2]["result"]["scale_factor"]["value"] = 36000.5;
  auto archive = open();
  EXPECT_EQ(error_of_add(*archive, twice),
            "bad/results.json: not an inertest results file: figure 'scale_factor/nonlinearity' appears twice (2 "
            "procedures are named 'scale_factor': give each step a name of its own)");
  const std::string good = scratch_.write("good.json", campaign("FOG-1", "2026-02-01", 36000.0).dump());
  const std::string bad = scratch_.write("twice.json", twice.dump());
  const auto refused = testing::run_cli({"archive", "add", good, bad, "--db", location_});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr(bad + ": not an inertest results file: figure 'scale_factor/nonlinearity' appears twice"));
  EXPECT_THAT(refused.err, Not(HasSubstr("UNIQUE")));
  EXPECT_TRUE(archive->list(std::nullopt).empty());

  // Several files in one transaction: the outcome of each, and a process killed while it writes
  // the second file's figures leaves neither file (the first one was committed on its own).
  const std::vector<std::pair<nlohmann::json, std::string>> files = {
      {campaign("FOG-1", "2026-02-01", 36000.0), "a.json"}, {campaign("FOG-3", "2026-02-03", 36000.0), "b.json"}};
  const auto outcomes = archive->add_all(files);
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_TRUE(outcomes[0].added && outcomes[1].added);
  EXPECT_EQ(archive->list(std::nullopt).size(), 2u);
  EXPECT_FALSE(archive->add_all(files)[1].added);  // the same content: stored once
  const std::string third = scratch_.write("c.json", campaign("FOG-4", "2026-02-04", 36000.0).dump());
  const std::string fourth = scratch_.write("d.json", campaign("FOG-5", "2026-02-05", 36000.0).dump());
  ::setenv("INERTEST_ARCHIVE_KILL_AFTER_FIGURES", "5", 1);  // killed in the second file's figures
  const auto killed = testing::run_cli({"archive", "add", third, fourth, "--db", location_});
  ::unsetenv("INERTEST_ARCHIVE_KILL_AFTER_FIGURES");
  EXPECT_EQ(killed.exit_code, 128 + 9) << killed.err;
  EXPECT_EQ(open()->list(std::nullopt).size(), 2u);  // neither FOG-4 nor FOG-5
}

// What add refuses, naming the file: a unit nothing converts (the figure's fleet then failed for every
// instrument), a nesting deep enough to exhaust the stack, a date with text after the day, and
// instrument ids that no page can reach.
TEST_P(ArchiveBackend, UnknownUnitsDeepNestingLooseDatesAndUnreachableIdsAreRefused) {
  auto archive = open();
  nlohmann::json unit = campaign("FOG-1", "2026-02-01", 36000.0);
  unit["procedures"][0]["result"]["scale_factor"]["unit"] = "furlong/fortnight";
  EXPECT_THAT(error_of_add(*archive, unit),
              HasSubstr("bad/results.json: not an inertest results file: figure 'scale_factor/scale_factor': \"unit\" "
                        "'furlong/fortnight': "));
  nlohmann::json deep = campaign("FOG-1", "2026-02-01", 36000.0);
  std::string nested;
  for (int i = 0; i < 20000; ++i) nested += "{\"a\":";
  nested += "1" + std::string(20000, '}');
  deep["procedures"][0]["result"]["deep"] = nlohmann::json::parse(nested);  // parsed without recursion
  EXPECT_EQ(error_of_add(*archive, deep), "bad/results.json: not an inertest results file: nested more than 64 levels deep");
  for (const char* date : {"2026-03-01garbage", "2026-03-01T10:00:00Z", "2026-03-01 10:00"}) {
    nlohmann::json loose = campaign("FOG-1", "2026-02-01", 36000.0);
    loose["tested_on"] = date;
    EXPECT_THAT(error_of_add(*archive, loose), HasSubstr(std::string("the test date '") + date + "' is not YYYY-MM-DD"));
  }
  for (const char* id : {".", "..", "FOG\n01", "FOG\x7f"}) {
    EXPECT_THAT(error_of_add(*archive, campaign(id, "2026-02-01", 36000.0)), HasSubstr("instrument: \"id\"")) << id;
  }
  EXPECT_TRUE(archive->list(std::nullopt).empty());
  EXPECT_EQ(error_of_add(*archive, campaign("FOG-1", "2026-02-01", 36000.0)), "no error");
}

INSTANTIATE_TEST_SUITE_P(Archive, ArchiveBackend, ::testing::Values("sqlite", "postgresql"),
                         [](const ::testing::TestParamInfo<const char*>& param) { return std::string(param.param); });

// Reading an archive that is not there is an error: a mistyped --db made an empty archive (and its
// directories) and listed nothing.
TEST(ArchiveOpening, AReadOfAMissingFileIsAnErrorAndCreatesNothing) {
  testing::ScratchDirectory scratch;
  const std::string typo = scratch.path() + "/typo/archive.sqlite";
  for (const std::vector<std::string>& command : {std::vector<std::string>{"list"}, {"instruments"},
                                                  {"history", "FOG-1", "--figure", "bias/bias"}}) {
    std::vector<std::string> arguments = {"archive"};
    arguments.insert(arguments.end(), command.begin(), command.end());
    arguments.insert(arguments.end(), {"--db", typo});
    const auto run = testing::run_cli(arguments);
    EXPECT_EQ(run.exit_code, 2) << command[0];
    EXPECT_THAT(run.err, HasSubstr(typo + ": no archive here (inertest archive add creates one)")) << command[0];
  }
  EXPECT_FALSE(std::filesystem::exists(scratch.path() + "/typo"));
}

// An archive this process cannot write (a file shared read-only, `inertest serve` run by a service
// account) is read as it is, and an add to it is refused, naming it and changing nothing. It failed
// with "attempt to write a readonly database": opening migrated, and SQLite's WAL needs its -shm
// file in the directory. The reading runs in a child process as nobody when this one is root (which
// file permissions do not stop); the child reports through a pipe.
TEST(ArchiveOpening, AnArchiveThisProcessCannotWriteIsRead) {
  testing::ScratchDirectory scratch;
  const std::string directory = scratch.path() + "/shared";
  const std::string path = directory + "/archive.sqlite";
  const auto id = open_archive(path, ArchiveOpening::create)->add(campaign("FOG-0417", "2026-02-01", 36000.2), "a.json").id;
  namespace fs = std::filesystem;
  fs::permissions(scratch.path(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                      fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(directory, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                 fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(path, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  int channel[2];
  ASSERT_EQ(::pipe(channel), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(channel[0]);
    nlohmann::json report;
    try {
      if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) throw std::runtime_error("cannot become nobody");
      auto archive = open_archive(path);
      report["listed"] = archive->list(std::nullopt).size();
      report["value"] = *archive->history("FOG-0417", "scale_factor/scale_factor").points.at(0).value;
      try {
        archive->add(campaign("FOG-0418", "2026-02-02", 36000.1), "b.json");
        report["add"] = "added";
      } catch (const Error& e) {
        report["add"] = e.what();
      }
    } catch (const std::exception& e) {
      report["error"] = e.what();
    }
    const std::string text = report.dump();
    const ssize_t written = ::write(channel[1], text.data(), text.size());
    ::_exit(written == static_cast<ssize_t>(text.size()) ? 0 : 1);
  }
  ::close(channel[1]);
  std::string text;
  char buffer[4096];
  for (ssize_t got; (got = ::read(channel[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(got));
  ::close(channel[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  fs::permissions(directory, fs::perms::owner_all, fs::perm_options::add);  // for the clean-up
  fs::permissions(path, fs::perms::owner_write, fs::perm_options::add);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  const auto report = nlohmann::json::parse(text);
  ASSERT_FALSE(report.contains("error")) << report.dump();
  EXPECT_EQ(report["listed"], 1);
  EXPECT_EQ(report["value"], 36000.2);
  EXPECT_EQ(report["add"], path + ": this process cannot write the archive (the file or its directory is read-only to it): "
                                  "nothing added");
  EXPECT_EQ(open_archive(path)->list(std::nullopt).size(), 1u);
  EXPECT_EQ(open_archive(path)->list(std::nullopt)[0].id, id);
}

// A server that accepts the connection and never answers: an error within seconds, not a hang.
TEST(ArchiveOpening, ASilentServerIsATimeoutNotAHang) {
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(listener, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(listener, 4), 0);
  socklen_t length = sizeof address;
  ASSERT_EQ(::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(open_archive(fmt::format("postgresql://lab@127.0.0.1:{}/archive", ntohs(address.sin_port))), Error);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  ::close(listener);
}

// A number beyond a double is the file's fault, named with its place (it was exit 3, "internal
// error: [json.exception.out_of_range.406]", no file named).
TEST(ArchiveFiles, ANumberBeyondADoubleIsTheFilesFault) {
  testing::ScratchDirectory scratch;
  const std::string file = scratch.write("results.json", "{\n  \"a\": {\n    \"value\": 1e400}}\n");
  try {
    read_results_file(file);
    FAIL() << "1e400 read";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), file + ":3:14: not valid JSON: number overflow parsing '1e400'");
  }
  const auto run = testing::run_cli({"archive", "add", file, "--db", scratch.path() + "/archive.sqlite"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_THAT(run.err, HasSubstr(file + ":3:14: not valid JSON: number overflow parsing '1e400'"));
}

// Another program's SQLite file named by --db (a typo, a wrong variable) is refused before anything
// in it changes: a read-only `archive list` created the archive's tables in it and turned it to WAL.
TEST(ArchiveOpening, AForeignDatabaseIsRefusedAndLeftAsItWas) {
  testing::ScratchDirectory scratch;
  const std::string foreign = scratch.path() + "/notes.sqlite";
  const auto sqlite = [](const std::string& path, const std::string& script) {
    const std::string command = fmt::format(
        "/usr/bin/python3 -c \"import sqlite3; c = sqlite3.connect('{}'); {}\"", path, script);
    return std::system(command.c_str());
  };
  ASSERT_EQ(sqlite(foreign, "c.execute('CREATE TABLE notes (x)'); c.commit()"), 0);
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"archive", "list", "--db", foreign}, {"archive", "instruments", "--db", foreign},
        {"archive", "fleet", "--figure", "a/b", "--db", foreign}}) {
    const auto run = testing::run_cli(command);
    EXPECT_EQ(run.exit_code, 2) << command[1];
    EXPECT_THAT(run.err, HasSubstr(foreign + ": not an inertest archive: the database holds other tables (notes) and "
                                             "no inertest schema"))
        << command[1];
  }
  const std::string good = scratch.write("good.json", campaign("FOG-1", "2026-02-01", 36000.0).dump());
  EXPECT_EQ(testing::run_cli({"archive", "add", good, "--db", foreign}).exit_code, 2);
  // Its tables and its rollback journal, as they were.
  EXPECT_EQ(sqlite(foreign, "import sys; sys.exit(0 if [r[0] for r in c.execute('SELECT name FROM sqlite_master')] == "
                            "['notes'] and c.execute('PRAGMA journal_mode').fetchone()[0] == 'delete' else 1)"),
            0);
  // An empty file (touched beforehand) is a new archive.
  const std::string empty = scratch.write("empty.sqlite", "");
  EXPECT_EQ(testing::run_cli({"archive", "add", good, "--db", empty}).exit_code, 0);
  EXPECT_EQ(testing::run_cli({"archive", "list", "--db", empty}).exit_code, 0);
}

// A damaged archive file is SQLite's error, said as it is: it was read as holding no archive, and
// the schema then created in the damaged file ("table campaign already exists").
TEST(ArchiveOpening, ACorruptArchiveIsSaidToBeSo) {
  testing::ScratchDirectory scratch;
  const std::string db = scratch.path() + "/archive.sqlite";
  for (const char* date : {"2026-02-01", "2026-02-02", "2026-02-03"}) {
    const std::string file = scratch.write(fmt::format("{}.json", date), campaign("FOG-1", date, 36000.0).dump());
    ASSERT_EQ(testing::run_cli({"archive", "add", file, "--db", db}).exit_code, 0);
  }
  {
    std::fstream file(db, std::ios::binary | std::ios::in | std::ios::out);
    file.seekp(4096);
    const std::string garbage(8192, '\xff');
    file.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }
  const auto run = testing::run_cli({"archive", "list", "--db", db});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(db + ": archive: database disk image is malformed"));
}

// A password in the URL is not printed, given as user:password@ or as a password= parameter.
TEST(ArchiveOpening, ThePasswordOfAUrlIsRedacted) {
  EXPECT_EQ(redact_postgresql_url("postgresql://lab:s3cret@db.lab:5432/archive"), "postgresql://lab:***@db.lab:5432/archive");
  EXPECT_EQ(redact_postgresql_url("postgresql://lab@127.0.0.1:1/archive?password=s3cret"),
            "postgresql://lab@127.0.0.1:1/archive?password=***");
  EXPECT_EQ(redact_postgresql_url("postgres://lab:a@h/db?sslmode=disable&password=s3cret&connect_timeout=2"),
            "postgres://lab:***@h/db?sslmode=disable&password=***&connect_timeout=2");
  EXPECT_EQ(redact_postgresql_url("postgresql://h/db?passfile=x"), "postgresql://h/db?passfile=x");
  const auto run = testing::run_cli({"archive", "list", "--db", "postgresql://lab@127.0.0.1:1/archive?password=s3cret"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("postgresql://lab@127.0.0.1:1/archive?password=***"));
  EXPECT_THAT(run.err, Not(HasSubstr("s3cret")));
}

// The PostgreSQL server dropping the connection (a restart; here the backend terminated): the next
// query connects again, as `inertest serve` needs to go on after a restart of the lab's server
// (every request was a 500 "no connection to the server" until serve itself was restarted).
TEST(ArchivePostgresql, ABrokenConnectionIsMadeAgainOnce) {
  auto& server = testing::PostgresqlServer::instance();
  ASSERT_TRUE(server.available()) << server.why_unavailable();
  const std::string location = server.create_database();
  auto archive = open_archive(location);
  archive->add(campaign("FOG-1", "2026-02-01", 36000.0), "a.json");
  const std::string command = fmt::format(
      "/usr/lib/postgresql/15/bin/psql -q '{}' -c 'SELECT pg_terminate_backend(pid) FROM pg_stat_activity WHERE "
      "datname = current_database() AND pid <> pg_backend_pid()' > /dev/null",
      location);
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(archive->list(std::nullopt).size(), 1u);
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_TRUE(archive->add(campaign("FOG-2", "2026-02-01", 36000.0), "b.json").added);  // a transaction too
  EXPECT_EQ(archive->list(std::nullopt).size(), 2u);
}

// A role that may only read (a lab's web view on the lab's server) opens the archive and reads it;
// an add is the server's refusal, naming the archive with its password hidden. Opening wrote
// (CREATE TABLE IF NOT EXISTS) and failed for such a role.
TEST(ArchivePostgresql, ARoleThatMayOnlyReadReadsTheArchive) {
  auto& server = testing::PostgresqlServer::instance();
  ASSERT_TRUE(server.available()) << server.why_unavailable();
  const std::string location = server.create_database();
  open_archive(location)->add(campaign("FOG-1", "2026-02-01", 36000.0), "a.json");
  const std::string role = "reader_" + location.substr(location.rfind('/') + 1);
  const std::string command = fmt::format(
      "/usr/lib/postgresql/15/bin/psql -q '{}' -c 'CREATE ROLE {} LOGIN' -c 'GRANT SELECT ON ALL TABLES IN SCHEMA "
      "public TO {}' > /dev/null",
      location, role, role);
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::string reader = location;
  reader.replace(reader.find("inertest@"), std::string("inertest").size(), role);
  auto archive = open_archive(reader);
  ASSERT_EQ(archive->list(std::nullopt).size(), 1u);
  EXPECT_EQ(archive->history("FOG-1", "scale_factor/scale_factor").points.at(0).value, 36000.0);
  EXPECT_THAT([&] { archive->add(campaign("FOG-2", "2026-02-02", 36000.0), "b.json"); },
              ::testing::ThrowsMessage<DatabaseError>(HasSubstr("permission denied")));
  EXPECT_EQ(open_archive(location)->list(std::nullopt).size(), 1u);
}

TEST(ArchiveLocation, DefaultIsTheEnvironmentThenHome) {
  const char* saved = std::getenv("INERTEST_DB");
  const std::string saved_value = saved ? saved : "";
  ::setenv("INERTEST_DB", "/srv/lab/archive.sqlite", 1);
  EXPECT_EQ(default_archive_location(), "/srv/lab/archive.sqlite");
  ::unsetenv("INERTEST_DB");
  EXPECT_EQ(default_archive_location(), std::string(std::getenv("HOME")) + "/.local/share/inertest/archive.sqlite");
  if (saved) ::setenv("INERTEST_DB", saved_value.c_str(), 1);
}

}  // namespace
}  // namespace inertest::archive
