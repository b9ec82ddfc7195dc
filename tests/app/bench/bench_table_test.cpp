// The shared output of `voxhap bench`: text table, JSON and CSV of synthetic rows.

#include "app/bench/bench_table.h"

#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/cli_runner.h"

namespace {

using voxhap::cli::BenchColumn;
using voxhap::cli::BenchStyle;
using voxhap::cli::BenchTable;

BenchTable sampleTable() {
  BenchTable table("sample", {{"name", "name", BenchStyle::Text},
                              {"size_m", "size mm", BenchStyle::Millimetres, 2},
                              {"count", "count", BenchStyle::Count},
                              {"big", "big", BenchStyle::Scientific},
                              {"time_s", "time s", BenchStyle::Fixed, 3}});
  const std::size_t a = table.addRow();
  table.set(a, "name", std::string("plain"));
  table.set(a, "size_m", 0.00035);
  table.set(a, "count", std::int64_t{1234567});
  table.set(a, "big", std::int64_t{459000000});
  table.set(a, "time_s", 1.5);
  const std::size_t b = table.addRow();
  table.set(b, "name", std::string("with, comma \"quoted\""));
  table.set(b, "size_m", 0.0007);
  table.set(b, "count", std::int64_t{7});
  table.set(b, "big", 3.11e6);
  return table;  // row b's time_s is not measured
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(BenchTable, JsonKeepsKeyOrderFullPrecisionAndNullForUnmeasured) {
  BenchTable table = sampleTable();
  table.extra["quick"] = true;
  const nlohmann::ordered_json j = voxhap::cli::benchJson(table);
  EXPECT_EQ(j.begin().key(), "benchmark");
  EXPECT_EQ(j["benchmark"], "sample");
  EXPECT_EQ(j["quick"], true);
  ASSERT_EQ(j["rows"].size(), 2u);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j["rows"][0].items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"name", "size_m", "count", "big", "time_s"}));
  EXPECT_EQ(j["rows"][0]["size_m"].get<double>(), 0.00035);
  EXPECT_EQ(j["rows"][0]["count"].get<std::int64_t>(), 1234567);
  EXPECT_TRUE(j["rows"][1]["time_s"].is_null());
}

TEST(BenchTable, CsvHasAHeaderOfKeysQuotesTextAndLeavesUnmeasuredEmpty) {
  std::ostringstream out;
  voxhap::cli::writeBenchCsv(out, sampleTable());
  const std::vector<std::string> l = lines(out.str());
  ASSERT_EQ(l.size(), 3u) << out.str();
  EXPECT_EQ(l[0], "name,size_m,count,big,time_s");
  EXPECT_EQ(l[1], "plain,0.00035,1234567,459000000,1.5");
  EXPECT_EQ(l[2], "\"with, comma \"\"quoted\"\"\",0.0007,7,3110000,");
}

TEST(BenchTable, TextTableAlignsColumnsAndShowsUnits) {
  std::ostringstream out;
  voxhap::cli::writeBenchText(out, sampleTable());
  const std::vector<std::string> l = lines(out.str());
  ASSERT_EQ(l.size(), 4u) << out.str();  // heading, rule, two rows
  EXPECT_NE(l[0].find("size mm"), std::string::npos);
  EXPECT_EQ(l[1].find_first_not_of("- "), std::string::npos) << l[1];
  EXPECT_NE(l[2].find("0.35"), std::string::npos) << l[2];
  EXPECT_NE(l[2].find("1,234,567"), std::string::npos) << l[2];
  EXPECT_NE(l[2].find("4.59e8"), std::string::npos) << l[2];
  EXPECT_NE(l[2].find("1.500"), std::string::npos) << l[2];
  EXPECT_NE(l[3].find("3.11e6"), std::string::npos) << l[3];
  EXPECT_EQ(l[3].back(), '-') << l[3];  // the unmeasured time
  // numbers are right-aligned: every row ends where the rule ends
  EXPECT_EQ(l[2].size(), l[1].size());
  EXPECT_EQ(l[3].size(), l[1].size());
}

TEST(BenchTable, AtGivesNothingForAnUnknownKey) {
  const BenchTable table = sampleTable();
  EXPECT_TRUE(std::holds_alternative<std::monostate>(table.at(0, "nope")));
  EXPECT_EQ(table.columnIndex("count"), 2u);
  EXPECT_EQ(table.columnIndex("nope"), table.columns().size());
}

TEST(BenchTable, WritesFilesWholeAndNamesTheFileOnFailure) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "voxhap-bench-table-test";
  std::filesystem::create_directories(dir);
  voxhap::cli::writeTextFileAtomically(dir / "t.csv", "a,b\n1,2\n");
  EXPECT_EQ(voxhap::test::slurp(dir / "t.csv"), "a,b\n1,2\n");
  try {
    voxhap::cli::writeTextFileAtomically(dir / "missing" / "t.csv", "x");
    ADD_FAILURE() << "no error";
  } catch (const voxhap::Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing/t.csv"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
