// Runs every entry of the bad-input corpus (tests/corpus/cases.json) through the CLI and checks its
// exit status, its exact error message (file:line:column included) and that nothing was written:
// stdout stays empty under --json and the --out directory is never created.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

struct CorpusCase {
  std::string name;
  nlohmann::json entry;
};

std::vector<CorpusCase> load_cases() {
  std::ifstream file(testing::source_path("tests/corpus/cases.json"));
  const nlohmann::json index = nlohmann::json::parse(file);
  std::vector<CorpusCase> cases;
  for (const auto& entry : index.at("cases")) cases.push_back({entry.at("name").get<std::string>(), entry});
  return cases;
}

std::string substitute(std::string text, const std::string& key, const std::string& value) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size())) {
    text.replace(at, key.size(), value);
  }
  return text;
}

// Files too big to keep in the repository, made on the fly.
void generate(const std::string& kind, const testing::ScratchDirectory& scratch) {
  ASSERT_EQ(kind, "huge_line");
  std::string text = "time,gyro\n0.00,0.0012\n0.01,";
  text.append(std::size_t{10} << 20, 'x');
  text += "\n0.02,0.0013\n";
  scratch.write("huge_line.csv", text);
}

class BadInputCorpus : public ::testing::TestWithParam<CorpusCase> {};

TEST_P(BadInputCorpus, GivesItsErrorAndNoOutput) {
  const nlohmann::json& entry = GetParam().entry;
  testing::ScratchDirectory scratch;
  if (entry.contains("generate")) generate(entry.at("generate").get<std::string>(), scratch);
  const std::string corpus = testing::source_path("tests/corpus");
  const std::string out = scratch.path() + "/out";
  auto expand = [&](const std::string& text) {
    return substitute(substitute(substitute(text, "{corpus}", corpus), "{out}", out), "{scratch}", scratch.path());
  };
  std::vector<std::string> arguments;
  for (const auto& argument : entry.at("args")) arguments.push_back(expand(argument.get<std::string>()));

  const testing::CliRun run = testing::run_cli(arguments);
  EXPECT_EQ(run.exit_code, entry.at("exit_code").get<int>()) << run.err;
  EXPECT_THAT(run.err, HasSubstr(expand(entry.at("stderr").get<std::string>())));
  if (entry.value("stdout", "empty") == "json") {
    EXPECT_TRUE(nlohmann::json::parse(run.out).is_object());
  } else {
    EXPECT_EQ(run.out, "");
  }
  EXPECT_FALSE(std::filesystem::exists(out)) << "an output directory was created";
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputCorpus, ::testing::ValuesIn(load_cases()), testing::NameOfParam());

}  // namespace
}  // namespace inertest
