// Typed configuration reading (common/config): ranges, non-finite numbers, unknown keys with the nearest
// valid name, and the file:line every error names.
#include <gtest/gtest.h>

#include <fstream>

#include "common/config/config_section.hpp"

using namespace ldv::config;

namespace {
std::string write_config_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string config_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(ConfigSection, GivenValidKeys_ThenTypedValuesAndDefaultsAreRead) {
  ConfigSection root =
      ConfigSection::load(write_config_file("ok.yaml", "rate_hz: 50\ntspi:\n  group: 239.255.77.1\n  ttl: 3\n"));
  EXPECT_DOUBLE_EQ(root.number("rate_hz", 1.0, Range::above(0.0).up_to(1000.0)), 50.0);
  EXPECT_DOUBLE_EQ(root.number("absent_s", 2.5), 2.5);
  ConfigSection t = root.section("tspi");
  EXPECT_EQ(t.text("group", ""), "239.255.77.1");
  EXPECT_EQ(t.integer("ttl", 1, 0, 255), 3);
  EXPECT_TRUE(root.section("absent").flag("print", true));
  EXPECT_NO_THROW(root.refuse_unknown());
}

TEST(ConfigSection, GivenZeroOrNanWhereAPositiveNumberIsNeeded_ThenTheErrorNamesFileLineKeyAndRange) {
  const std::string path = write_config_file("bad.yaml", "bus_url: x\ntsu:\n  counter_hz: 0\nsample_rate_hz: .nan\n");
  ConfigSection root = ConfigSection::load(path);
  ConfigSection tsu = root.section("tsu");
  EXPECT_EQ(config_error_of([&] { tsu.number("counter_hz", 1e7, Range::above(0.0)); }),
            path + ":3: tsu.counter_hz: expected a number > 0, found 0");
  EXPECT_EQ(config_error_of([&] { root.number("sample_rate_hz", 100.0, Range::above(0.0)); }),
            path + ":4: sample_rate_hz: expected a number > 0, found .nan");
}

TEST(ConfigSection, GivenAMisspeltKey_ThenRefuseUnknownNamesItsLineAndTheNearestValidKey) {
  const std::string path = write_config_file("typo.yaml", "tspi:\n  rate_hz: 50\n  chanel: TSPI\n");
  ConfigSection root = ConfigSection::load(path);
  ConfigSection t = root.section("tspi");
  t.number("rate_hz", 50.0);
  t.text("channel", "TSPI");
  EXPECT_EQ(config_error_of([&] { root.refuse_unknown(); }),
            path + ":3: unknown key 'tspi.chanel' (did you mean 'channel'?)");
}

TEST(ConfigSection, GivenAWrongType_ThenTheErrorSaysWhatWasExpected) {
  const std::string path = write_config_file("type.yaml", "ttl: three\nmode: fastest\nrpy: [1, 2]\n");
  ConfigSection root = ConfigSection::load(path);
  EXPECT_EQ(config_error_of([&] { root.integer("ttl", 1, 0, 255); }),
            path + ":1: ttl: expected an integer in [0, 255], found 'three'");
  EXPECT_EQ(config_error_of([&] {
              root.choice("mode", "fast", {"fast", "slow"});
            }),
            path + ":2: mode: expected one of fast, slow, found 'fastest'");
  EXPECT_EQ(config_error_of([&] {
              root.numbers("rpy", {0, 0, 0}, 3);
            }),
            path + ":3: rpy: expected a list of 3 numbers finite");
}

TEST(ConfigSection, NearestNameSuggestsOnlyTypos) {
  EXPECT_EQ(nearest_name("rate_hzz", {"rate_hz", "ttl"}), "rate_hz");
  EXPECT_EQ(nearest_name("completely_else", {"rate_hz", "ttl"}), "");
}
