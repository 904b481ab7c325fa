// The archive's listings as JSON, shared by the CLI (`archive list`, `archive instruments`) and
// the web view's API (`inertest serve`), so that both give the same objects.
#include <map>

#include "inertest/archive/archive.h"

namespace inertest::archive {
namespace {

nlohmann::json entry_json(const CampaignEntry& e) {
  return {{"id", e.id},
          {"instrument", e.instrument},
          {"title", e.title},
          {"tested_on", e.tested_on},
          {"processed_at", e.processed_at},
          {"verdict", e.verdict},
          {"superseded_by", e.superseded_by}};
}

}  // namespace

nlohmann::json campaign_list_json(const std::vector<CampaignEntry>& campaigns) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& e : campaigns) list.push_back(entry_json(e));
  return {{"campaigns", std::move(list)}};
}

nlohmann::json instrument_list_json(const std::vector<CampaignEntry>& campaigns) {
  struct Instrument {
    std::size_t campaigns = 0;
    const CampaignEntry* latest = nullptr;
  };
  std::map<std::string, Instrument> instruments;  // sorted by id
  for (const auto& e : campaigns) {
    Instrument& instrument = instruments[e.instrument];
    ++instrument.campaigns;
    instrument.latest = &e;  // campaigns come oldest test first
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [id, instrument] : instruments) {
    list.push_back({{"instrument", id}, {"campaigns", instrument.campaigns}, {"latest", entry_json(*instrument.latest)}});
  }
  return {{"instruments", std::move(list)}};
}

}  // namespace inertest::archive
