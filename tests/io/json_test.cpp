// JSON files as the summaries use them: what is written reads back the same with keys in
// insertion order, NaN becomes null, bytes that are not UTF-8 do not lose the file, and a
// missing or malformed file is an error naming it (and, for bad text, the byte offset).
#include "hylo/io/json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "test_data.h"

namespace hylo::io {
namespace {

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadJsonFile(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(JsonTest, WrittenFileReadsBackWithKeysInInsertionOrder) {
  Json j;
  j["backend"] = "sliding_window";
  j["scans"] = 240;
  j["ms"] = 8.25;
  j["tiny"] = 1.5e-12;
  j["negative"] = -3;
  j["flag"] = true;
  j["none"] = nullptr;
  j["c2c"]["mean_m"] = 0.031;
  j["events"].push_back("initialized");
  j["events"].push_back(Json::array({1.0, 2.5}));
  j["text"] = "quote \" backslash \\ tab \t newline \n";
  const std::string path = testing::ScratchDir("json_io") + "/summary.json";
  WriteJsonFile(path, j);
  const Json back = ReadJsonFile(path);
  EXPECT_EQ(back, j);
  EXPECT_EQ(DumpJson(back), DumpJson(j));
  std::vector<std::string> keys;
  for (const auto& member : back.items()) keys.push_back(member.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"backend", "scans", "ms", "tiny", "negative", "flag",
                                            "none", "c2c", "events", "text"}));
  EXPECT_TRUE(back.at("scans").is_number_integer()) << "integers stay integers";
}

TEST(JsonTest, NonFiniteNumbersAreWrittenAsNull) {
  Json j;
  j["nan"] = std::numeric_limits<double>::quiet_NaN();
  j["inf"] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(DumpJson(j, -1), R"({"nan":null,"inf":null})");
}

TEST(JsonTest, BytesThatAreNotUtf8AreReplacedNotThrown) {
  Json j;
  j["path"] = std::string("/data/caf\xe9.bag");  // Latin-1 e-acute
  const std::string path = testing::ScratchDir("json_io") + "/latin1.json";
  WriteJsonFile(path, j);
  EXPECT_EQ(ReadJsonFile(path).at("path"), "/data/caf\xEF\xBF\xBD.bag");  // U+FFFD
}

TEST(JsonTest, NumberAtFollowsDottedPaths) {
  const std::string path = testing::ScratchDir("json_io") + "/paths.json";
  WriteText(path, R"({"a": {"b": [1, 2]}, "x": -0.5e2, "big": 12345678901234567890,
                      "u": "\u00e9\ud83d\ude00", "n": null, "s": "7", "c2c": {"mean_m": 0.031}})");
  const Json j = ReadJsonFile(path);
  EXPECT_DOUBLE_EQ(NumberAt(j, "x"), -50.0);
  EXPECT_DOUBLE_EQ(NumberAt(j, "big"), 12345678901234567890.0);
  EXPECT_DOUBLE_EQ(NumberAt(j, "c2c.mean_m"), 0.031);
  EXPECT_EQ(j.at("u"), "\xC3\xA9\xF0\x9F\x98\x80");
  EXPECT_TRUE(std::isnan(NumberAt(j, "n")));
  EXPECT_TRUE(std::isnan(NumberAt(j, "s")));    // a string is not a number
  EXPECT_TRUE(std::isnan(NumberAt(j, "a.c")));  // absent
  EXPECT_TRUE(std::isnan(NumberAt(j, "a.b")));  // an array is not a number
  EXPECT_TRUE(std::isnan(NumberAt(j, "x.y")));  // through a number
  EXPECT_TRUE(std::isnan(NumberAt(j, "")));
}

TEST(JsonTest, MalformedTextNamesTheFileAndTheByteOffset) {
  const std::string dir = testing::ScratchDir("json_io");
  const char* bad[] = {"",       "{",   "{\"a\" 1}",  "[1, 2", "{\"a\": tru}",
                       "\"open", "1 2", "{\"a\": -}", "[1,]",  "\"bad \\q escape\""};
  for (const char* text : bad) {
    WriteText(dir + "/bad.json", text);
    const std::string what = ErrorOf(dir + "/bad.json");
    EXPECT_NE(what.find("bad.json': not valid JSON at byte "), std::string::npos) << what;
    EXPECT_EQ(what.find("[json.exception"), std::string::npos) << what;
  }
  WriteText(dir + "/bad.json", "{\"a\": 1,\n \"b\": ]}");
  const std::string what = ErrorOf(dir + "/bad.json");
  EXPECT_NE(what.find("at byte 16"), std::string::npos) << what;
  EXPECT_NE(what.find("line 2"), std::string::npos) << what;
}

TEST(JsonTest, MissingOrUnwritableFileIsAnErrorNamingIt) {
  EXPECT_NE(ErrorOf("/nonexistent/summary.json").find("'/nonexistent/summary.json': cannot open"),
            std::string::npos);
  try {
    WriteJsonFile("/nonexistent/out.json", Json::object());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/out.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hylo::io
