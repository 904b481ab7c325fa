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

nlohmann::json history_data(Archive& archive, const std::string& instrument, const std::vector<std::string>& figures) {
  const std::vector<std::string> archived = archive.figures(false);
  nlohmann::json list = nlohmann::json::array();
  nlohmann::json not_comparable = nlohmann::json::array();
  for (const auto& figure : figures) {
    if (!std::binary_search(archived.begin(), archived.end(), figure)) continue;
    try {
      list.push_back(archive.history(instrument, figure).to_json());
    } catch (const DatabaseError&) {
      throw;
    } catch (const NotOneQuantity& e) {
      // The instrument's own campaigns measured two quantities under the name: said, not left out.
      not_comparable.push_back({{"figure", figure}, {"why", e.message()}});
    } catch (const Error&) {
      // this instrument's campaigns do not report the figure
    }
  }
  return {{"instrument", instrument}, {"figures", list}, {"not_comparable", not_comparable}};
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
  const std::vector<std::string> archived = archive.figures(false);
  nlohmann::json fleet = nlohmann::json::array();
  nlohmann::json not_comparable = nlohmann::json::array();
  for (const auto& figure : figures) {
    if (!std::binary_search(archived.begin(), archived.end(), figure)) continue;
    try {
      fleet.push_back(fleet_summary(archive.fleet(figure, since), since));
    } catch (const DatabaseError&) {
      throw;
    } catch (const NotOneQuantity& e) {
      not_comparable.push_back({{"figure", figure}, {"why", e.message()}});
    } catch (const Error&) {
      if (!since) throw;
      // no test of the figure since then: not on the page (the page was a 404)
    }
  }
  return {{"fleet", fleet}, {"not_comparable", not_comparable}};
}

}  // namespace inertest::archive
