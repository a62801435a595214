// Reading JSON back: what io::Json writes parses to the same text, escapes and numbers keep
// their values, malformed text is an error naming the source and the byte offset.
#include "hylo/report/json_reader.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hylo::report {
namespace {

TEST(JsonReaderTest, RoundTripsWhatIoJsonWrites) {
  io::Json j = io::Json::MakeObject();
  j["backend"] = "sliding_window";
  j["scans"] = 240;
  j["ms"] = 8.25;
  j["tiny"] = 1.5e-12;
  j["negative"] = -3;
  j["flag"] = true;
  j["none"] = io::Json();
  j["c2c"]["mean_m"] = 0.031;
  j["events"].PushBack("initialized");
  j["events"].PushBack(io::Json::FromNumbers({1.0, 2.5}));
  j["text"] = "quote \" backslash \\ tab \t newline \n";
  const std::string text = j.Dump();
  EXPECT_EQ(ParseJson(text, "test").Dump(), text);
  EXPECT_EQ(ParseJson(j.Dump(-1), "test").Dump(), text);
}

TEST(JsonReaderTest, NumbersEscapesAndPaths) {
  const io::Json j = ParseJson(
      R"({"a": {"b": [1, 2]}, "x": -0.5e2, "big": 12345678901234567890, "u": "\u00e9\ud83d\ude00",
          "n": null, "s": "7"})",
      "inline");
  EXPECT_DOUBLE_EQ(NumberAt(j, "x"), -50.0);
  EXPECT_DOUBLE_EQ(NumberAt(j, "big"), 12345678901234567890.0);
  EXPECT_EQ(*j.Find("u")->AsString(), "\xC3\xA9\xF0\x9F\x98\x80");
  EXPECT_TRUE(std::isnan(NumberAt(j, "n")));
  EXPECT_TRUE(std::isnan(NumberAt(j, "s")));    // a string is not a number
  EXPECT_TRUE(std::isnan(NumberAt(j, "a.c")));  // absent
  EXPECT_TRUE(std::isnan(NumberAt(j, "x.y")));  // through a number
  EXPECT_EQ(j.Find("a")->Find("b")->AsArray()->size(), 2u);
}

TEST(JsonReaderTest, MalformedTextNamesSourceAndOffset) {
  const char* bad[] = {"",       "{",   "{\"a\" 1}",  "[1, 2", "{\"a\": tru}",
                       "\"open", "1 2", "{\"a\": -}", "[1,]",  "\"bad \\q escape\""};
  for (const char* text : bad) {
    try {
      ParseJson(text, "summary.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("summary.json: JSON error at byte"), std::string::npos) << what;
    }
  }
}

TEST(JsonReaderTest, MissingFileIsAnErrorNamingIt) {
  try {
    ReadJsonFile("/nonexistent/summary.json");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/summary.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace hylo::report
