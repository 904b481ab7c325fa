// The fleet's view of one figure and the data of the archive's report pages: plain data from the
// archive's queries plus the control chart of numerics/control_chart.h.
#include <algorithm>
#include <map>

#include "inertest/archive/archive.h"
#include "inertest/core/error.h"
#include "inertest/numerics/control_chart.h"

namespace inertest::archive {
namespace {

nlohmann::json optional_json(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json fleet_summary(const FleetFigure& fleet, const std::optional<std::string>& since) {
  // Each instrument's latest value (points come by instrument, then test date), keyed by the
  // instrument's first test date then its id: the order the batch came off the line.
  struct Instrument {
    std::string first_test;
    const FigurePoint* latest = nullptr;
    std::size_t tests = 0;
  };
  std::map<std::string, Instrument> by_id;
  for (const auto& p : fleet.points) {
    auto [it, inserted] = by_id.try_emplace(p.instrument, Instrument{p.tested_on, &p, 0});
    it->second.latest = &p;
    ++it->second.tests;
  }
  std::vector<const Instrument*> order;
  for (const auto& [id, instrument] : by_id) order.push_back(&instrument);
  std::stable_sort(order.begin(), order.end(),
                   [](const Instrument* a, const Instrument* b) { return a->first_test < b->first_test; });
  // The chart and the indices are over the measured latest values; an instrument whose latest test
  // did not measure the figure is listed with a null value, not with an older one.
  std::vector<double> values;
  std::vector<std::size_t> measured;  // measured[k]: the place in instruments of values[k]
  nlohmann::json instruments = nlohmann::json::array();
  for (const Instrument* i : order) {
    const FigurePoint& p = *i->latest;
    if (p.value) {
      values.push_back(*p.value);
      measured.push_back(instruments.size());
    }
    instruments.push_back({{"instrument", p.instrument}, {"value", optional_json(p.value)},
                           {"uncertainty", optional_json(p.uncertainty)}, {"tested_on", p.tested_on},
                           {"campaign", p.campaign}, {"tests", i->tests}});
  }
  nlohmann::json json = {{"figure", fleet.figure},
                         {"unit", fleet.unit},
                         {"since", since ? nlohmann::json(*since) : nlohmann::json(nullptr)},
                         {"lower_limit", optional_json(fleet.lower_limit)},
                         {"upper_limit", optional_json(fleet.upper_limit)},
                         {"limit_on_magnitude", fleet.limit_on_magnitude},
                         {"instruments", instruments},
                         {"control_chart", nullptr},
                         {"capability", {{"cp", nullptr}, {"cpk", nullptr}}}};
  if (fleet.place) json["place"] = *fleet.place;
  if (values.size() < 2) return json;  // one measured instrument: no moving range
  const ControlChart chart = individuals_control_chart(values);
  nlohmann::json flagged = nlohmann::json::array();
  for (const auto& o : chart.out_of_control) {
    flagged.push_back({{"instrument", instruments[measured[o.index]]["instrument"]}, {"value", values[o.index]}, {"rule", o.rule}});
  }
  json["control_chart"] = {{"center", chart.center},
                           {"ucl", chart.ucl},
                           {"lcl", chart.lcl},
                           {"moving_range_mean", chart.moving_range_mean},
                           {"sigma", chart.sigma},
                           {"out_of_control", flagged}};
  if (chart.sigma > 0.0) {
    const ProcessCapability capability = process_capability(chart.center, chart.sigma, fleet.lower_limit, fleet.upper_limit);
    json["capability"] = {{"cp", optional_json(capability.cp)}, {"cpk", optional_json(capability.cpk)}};
  }
  return json;
}

namespace {

// Of `figures`, those the archive holds: what `summary` makes of each (into "figures"), and those
// archived in units that do not convert ({"figure", "why"} into "not_comparable"). Another Error of
// a figure (none of the instrument's, none since the date) leaves it out when `absent_is_expected`.
template <typename Summary>
nlohmann::json each_archived_figure(Archive& archive, const std::vector<std::string>& figures,
                                    bool absent_is_expected, const Summary& summary) {
  const std::vector<std::string> archived = archive.figures(false);
  nlohmann::json made = nlohmann::json::array();
  nlohmann::json not_comparable = nlohmann::json::array();
  for (const auto& figure : figures) {
    if (!std::binary_search(archived.begin(), archived.end(), figure)) continue;
    try {
      made.push_back(summary(figure));
    } catch (const DatabaseError&) {
      throw;
    } catch (const NotOneQuantity& e) {
      not_comparable.push_back({{"figure", figure}, {"why", e.message()}});
    } catch (const Error&) {
      if (!absent_is_expected) throw;
    }
  }
  return {{"figures", made}, {"not_comparable", not_comparable}};
}

}  // namespace

nlohmann::json history_data(Archive& archive, const std::string& instrument, const std::vector<std::string>& figures) {
  nlohmann::json data = each_archived_figure(archive, figures, true, [&](const std::string& figure) {
    return archive.history(instrument, figure).to_json();
  });
  data["instrument"] = instrument;
  return data;
}

nlohmann::json report_data(Archive& archive, const std::vector<std::string>& figures) {
  std::vector<std::string> instruments;
  for (const auto& campaign : archive.list(std::nullopt)) instruments.push_back(campaign.instrument);
  std::sort(instruments.begin(), instruments.end());
  instruments.erase(std::unique(instruments.begin(), instruments.end()), instruments.end());
  nlohmann::json histories = nlohmann::json::array();
  for (const auto& instrument : instruments) histories.push_back(history_data(archive, instrument, figures));
  nlohmann::json data = fleet_data(archive, figures, std::nullopt);
  data["histories"] = std::move(histories);
  return data;
}

nlohmann::json fleet_data(Archive& archive, const std::vector<std::string>& figures,
                          const std::optional<std::string>& since) {
  // A figure no test since the date reports is left off (the web view's page was a 404 for it).
  nlohmann::json data = each_archived_figure(archive, figures, since.has_value(), [&](const std::string& figure) {
    return fleet_summary(archive.fleet(figure, since), since);
  });
  return {{"fleet", std::move(data.at("figures"))}, {"not_comparable", std::move(data.at("not_comparable"))}};
}

}  // namespace inertest::archive
