// The sdel.json handoff (common/include/uhpc/sdel_handoff.hpp): round trip, the shipped paper file,
// and the exact message of each validation error.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "uhpc/errors.hpp"
#include "test_support.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace {

using nlohmann::json;

template <typename F>
std::string input_error_of(F&& f) {
  return uhpc::test::error_of<uhpc::InputError>(f);
}

// A valid document to break one key at a time.
json valid_document() {
  return json::parse(R"({
    "format": "uhpc-sdel/1",
    "law": "informative text",
    "constants": {"a": 1.0, "A": 0.0002, "nu": 120.5, "chi": 4.1e6},
    "l_mac_m": 0.4064,
    "strain_measure": "mazars_equivalent_tensile",
    "cell_sizes_m": [0.003, 0.0045, 0.005, 0.0065],
    "source": "test"
  })");
}

std::string error_of(const json& document) {
  return input_error_of([&] { (void)uhpc::sdel_handoff_from_json(document, "sdel.json"); });
}

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::path(UHPC_BINARY_DIR) / ("test_sdel_handoff_" + name);
}

TEST(SdelHandoff, RoundTrip) {
  uhpc::SdelHandoff h;
  h.constants = {0.731, 2.13e-4, 98.25, 3.3e6 + 0.1};
  h.l_mac_m = 0.4064;
  h.strain_measure = "max_principal_tensile";
  h.cell_sizes_m = {0.003, 0.0045, 0.005, 0.0065};
  h.fit = {{"rms_per_size", {0.01, 0.02, 0.03, 0.04}}, {"covariance", {{1.0, 0.1}, {0.1, 2.0}}}};
  h.source = "uhpc-calibrate on ensemble.h5";
  h.provenance = uhpc::Provenance{"uhpc-calibrate", "0.1.0", "abc123", "00ff", "2026-01-01T00:00:00Z", 42u};

  const std::filesystem::path path = temp_file("round_trip.json");
  uhpc::write_sdel_handoff(path.string(), h);
  const uhpc::SdelHandoff r = uhpc::read_sdel_handoff(path.string());
  EXPECT_EQ(r.constants.a, h.constants.a);  // exact: doubles are written in round-trip precision
  EXPECT_EQ(r.constants.A, h.constants.A);
  EXPECT_EQ(r.constants.nu, h.constants.nu);
  EXPECT_EQ(r.constants.chi, h.constants.chi);
  EXPECT_EQ(r.l_mac_m, h.l_mac_m);
  EXPECT_EQ(r.strain_measure, h.strain_measure);
  EXPECT_EQ(r.cell_sizes_m, h.cell_sizes_m);
  EXPECT_EQ(r.fit, h.fit);
  EXPECT_EQ(r.source, h.source);
  ASSERT_TRUE(r.provenance.has_value());
  EXPECT_EQ(r.provenance->to_json(), h.provenance->to_json());

  // The file carries the format and the law text, and lists "format" first.
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("\"format\""), text.find('"'));
  const json written = json::parse(text);
  EXPECT_EQ(written.at("format"), "uhpc-sdel/1");
  EXPECT_EQ(written.at("law"), std::string(uhpc::kSdelLawText));
  std::filesystem::remove(path);
}

TEST(SdelHandoff, OptionalBlocksMayBeAbsent) {
  json d = valid_document();
  d.erase("law");
  d.erase("strain_measure");
  const uhpc::SdelHandoff h = uhpc::sdel_handoff_from_json(d, "sdel.json");
  EXPECT_EQ(h.strain_measure, "effective_tensile_strain");  // the default
  EXPECT_FALSE(h.provenance.has_value());
  EXPECT_TRUE(h.fit.is_object());
  EXPECT_TRUE(h.fit.empty());
}

TEST(SdelHandoff, PaperFileGivesTable4) {
  const uhpc::SdelHandoff h = uhpc::read_sdel_handoff(std::string(UHPC_DATA_DIR) + "/sdel_paper.json");
  EXPECT_EQ(h.constants.a, 1.0);
  EXPECT_EQ(h.constants.A, 0.0002);
  EXPECT_EQ(h.constants.nu, 120.5);
  EXPECT_EQ(h.constants.chi, 4.1e6);
  EXPECT_EQ(h.l_mac_m, 0.4064);
  EXPECT_EQ(h.strain_measure, "effective_tensile_strain");
  EXPECT_EQ(h.cell_sizes_m, (std::vector<double>{0.003, 0.0045, 0.005, 0.0065}));
  EXPECT_FALSE(h.source.empty());
  EXPECT_TRUE(h.fit.contains("notes"));
}

TEST(SdelHandoff, UnknownKey) {
  json d = valid_document();
  d["colour"] = "red";
  EXPECT_EQ(error_of(d), "sdel.json: key 'colour': unknown key");
  json e = valid_document();
  e["constants"]["kappa"] = 4.1e6;
  EXPECT_EQ(error_of(e), "sdel.json: key 'constants.kappa': unknown key");
}

TEST(SdelHandoff, MissingConstant) {
  json d = valid_document();
  d["constants"].erase("chi");
  EXPECT_EQ(error_of(d), "sdel.json: key 'constants.chi': required key is missing");
  json e = valid_document();
  e.erase("constants");
  EXPECT_EQ(error_of(e), "sdel.json: key 'constants': required key is missing");
}

TEST(SdelHandoff, NonPositiveValues) {
  json d = valid_document();
  d["constants"]["nu"] = -120.5;
  EXPECT_EQ(error_of(d), "sdel.json: key 'constants.nu': value -120.5 is out of range, must be > 0");
  json e = valid_document();
  e["l_mac_m"] = 0.0;
  EXPECT_EQ(error_of(e), "sdel.json: key 'l_mac_m': value 0 is out of range, must be > 0");
  json f = valid_document();
  f["cell_sizes_m"][2] = -0.005;
  EXPECT_EQ(error_of(f), "sdel.json: key 'cell_sizes_m[2]': value -0.005 is out of range, must be > 0");
}

TEST(SdelHandoff, WrongType) {
  json d = valid_document();
  d["constants"]["A"] = "0.0002";
  EXPECT_EQ(error_of(d), "sdel.json: key 'constants.A': expected a number, got a string");
  json e = valid_document();
  e["fit"] = "good";
  EXPECT_EQ(error_of(e), "sdel.json: key 'fit': expected an object, got a string");
}

TEST(SdelHandoff, BadFormatString) {
  json d = valid_document();
  d["format"] = "uhpc-sdel/2";
  EXPECT_EQ(error_of(d), "sdel.json: key 'format': expected \"uhpc-sdel/1\", got \"uhpc-sdel/2\"");
  json e = valid_document();
  e.erase("format");
  EXPECT_EQ(error_of(e), "sdel.json: key 'format': required key is missing");
}

TEST(SdelHandoff, BadStrainMeasure) {
  json d = valid_document();
  d["strain_measure"] = "von_mises";
  EXPECT_EQ(error_of(d),
            "sdel.json: key 'strain_measure': value 'von_mises' is not one of: effective_tensile_strain, "
            "mazars_equivalent_tensile, max_principal_tensile");
}

TEST(SdelHandoff, MalformedProvenance) {
  json d = valid_document();
  d["provenance"] = {{"program", "x"}};
  EXPECT_EQ(error_of(d), "sdel.json: key 'provenance': missing key 'version'");
}

TEST(SdelHandoff, MissingFile) {
  const std::string path = temp_file("does_not_exist.json").string();
  const std::string message = input_error_of([&] { (void)uhpc::read_sdel_handoff(path); });
  EXPECT_EQ(message.rfind(path + ": cannot open file", 0), 0u) << message;
}

TEST(SdelHandoff, WriterRefusesAnInvalidHandoff) {
  uhpc::SdelHandoff h;
  h.constants = {1.0, 0.0002, -1.0, 4.1e6};
  h.cell_sizes_m = {0.003};
  h.source = "test";
  const std::filesystem::path path = temp_file("invalid.json");
  EXPECT_THROW(uhpc::write_sdel_handoff(path.string(), h), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
