// The provenance block: filled from the build and the clock, and a JSON round trip that keeps
// every field exactly (a 64-bit seed included) and rejects malformed blocks with the key named.
#include "uhpc/provenance.hpp"

#include <cstdint>
#include <ctime>
#include <limits>
#include <regex>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "uhpc/build_info.hpp"

using uhpc::Provenance;

namespace {

Provenance sample(std::optional<std::uint64_t> seed) {
  Provenance p;
  p.program = "uhpc-micro run";
  p.version = "0.1.0";
  p.git_commit = "0123456789abcdef0123456789abcdef01234567-dirty";
  p.config_hash = "cbf29ce484222325";
  p.date_utc = "2026-11-21T23:59:01Z";
  p.seed = seed;
  return p;
}

void expect_equal(const Provenance& a, const Provenance& b) {
  EXPECT_EQ(a.program, b.program);
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.git_commit, b.git_commit);
  EXPECT_EQ(a.config_hash, b.config_hash);
  EXPECT_EQ(a.date_utc, b.date_utc);
  EXPECT_EQ(a.seed, b.seed);
}

// The message of the std::runtime_error thrown by from_json, or "" if none was thrown.
std::string from_json_error(const nlohmann::json& j) {
  try {
    Provenance::from_json(j);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Provenance, MakeFillsBuildInfoAndUtcDate) {
  const std::time_t before = std::time(nullptr);
  const Provenance p = Provenance::make("uhpc-macro", "abc123", 42u);
  const std::time_t after = std::time(nullptr);

  EXPECT_EQ(p.program, "uhpc-macro");
  EXPECT_EQ(p.version, uhpc::build_version());
  EXPECT_EQ(p.git_commit, uhpc::build_git_commit());
  EXPECT_EQ(p.config_hash, "abc123");
  ASSERT_TRUE(p.seed.has_value());
  EXPECT_EQ(*p.seed, 42u);
  ASSERT_TRUE(std::regex_match(p.date_utc, std::regex(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}Z)"))) << p.date_utc;

  // The date is the current time in UTC (not local time).
  std::tm tm{};
  ASSERT_NE(strptime(p.date_utc.c_str(), "%Y-%m-%dT%H:%M:%SZ", &tm), nullptr);
  const std::time_t stamped = timegm(&tm);
  EXPECT_GE(stamped, before);
  EXPECT_LE(stamped, after);
}

TEST(Provenance, MakeWithoutSeed) {
  EXPECT_FALSE(Provenance::make("uhpc-calibrate", "").seed.has_value());
}

TEST(Provenance, JsonHasExactlyTheDocumentedKeys) {
  const nlohmann::json j = sample(7u).to_json();
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.size(), 6u);
  EXPECT_EQ(j.at("program"), "uhpc-micro run");
  EXPECT_EQ(j.at("version"), "0.1.0");
  EXPECT_EQ(j.at("git_commit"), "0123456789abcdef0123456789abcdef01234567-dirty");
  EXPECT_EQ(j.at("config_hash"), "cbf29ce484222325");
  EXPECT_EQ(j.at("date_utc"), "2026-11-21T23:59:01Z");
  EXPECT_EQ(j.at("seed"), 7u);
}

TEST(Provenance, AbsentSeedIsNull) {
  const nlohmann::json j = sample(std::nullopt).to_json();
  ASSERT_TRUE(j.contains("seed"));
  EXPECT_TRUE(j.at("seed").is_null());
  EXPECT_FALSE(Provenance::from_json(j).seed.has_value());
}

TEST(Provenance, RoundTripThroughJsonTextKeepsLargestSeed) {
  const std::uint64_t max_seed = std::numeric_limits<std::uint64_t>::max();
  const std::string text = sample(max_seed).to_json().dump();
  EXPECT_NE(text.find("18446744073709551615"), std::string::npos) << text;
  const Provenance back = Provenance::from_json(nlohmann::json::parse(text));
  expect_equal(back, sample(max_seed));
  EXPECT_EQ(*back.seed, max_seed);
}

TEST(Provenance, RoundTripKeepsSeedsAroundDoublePrecisionLimit) {
  for (std::uint64_t seed : {std::uint64_t{0}, (std::uint64_t{1} << 53) + 1, std::uint64_t{1} << 63}) {
    const Provenance back = Provenance::from_json(nlohmann::json::parse(sample(seed).to_json().dump()));
    EXPECT_EQ(back.seed, seed);
  }
}

TEST(Provenance, AcceptsSignedNonNegativeSeedAndIgnoresExtraKeys) {
  nlohmann::json j = sample(std::nullopt).to_json();
  j["seed"] = std::int64_t{12};
  j["host"] = "node17";  // newer writers may add keys; readers keep working
  EXPECT_EQ(Provenance::from_json(j).seed, std::uint64_t{12});
}

TEST(Provenance, MissingKeysAreNamed) {
  for (const char* key : {"program", "version", "git_commit", "config_hash", "date_utc", "seed"}) {
    nlohmann::json j = sample(1u).to_json();
    j.erase(key);
    const std::string message = from_json_error(j);
    EXPECT_NE(message.find(std::string("'") + key + "'"), std::string::npos) << key << ": " << message;
    EXPECT_NE(message.find("missing"), std::string::npos) << message;
  }
}

TEST(Provenance, MistypedFieldsAreRejected) {
  nlohmann::json j = sample(1u).to_json();
  j["program"] = 3;
  EXPECT_NE(from_json_error(j).find("key 'program': expected a string, got number"), std::string::npos)
      << from_json_error(j);

  for (const nlohmann::json& bad_seed :
       {nlohmann::json(-1), nlohmann::json(1.5), nlohmann::json("12"), nlohmann::json::array({1})}) {
    j = sample(1u).to_json();
    j["seed"] = bad_seed;
    const std::string message = from_json_error(j);
    EXPECT_NE(message.find("key 'seed'"), std::string::npos) << bad_seed.dump() << ": " << message;
  }
}

TEST(Provenance, NonObjectIsRejected) {
  EXPECT_THROW(Provenance::from_json(nlohmann::json::array()), std::runtime_error);
  EXPECT_THROW(Provenance::from_json(nlohmann::json("text")), std::runtime_error);
  EXPECT_THROW(Provenance::from_json(nlohmann::json()), std::runtime_error);
}
