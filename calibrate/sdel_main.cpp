// uhpc-sdel: what an SDEL handoff (sdel.json) means at given length scales.
//
//   uhpc-sdel --config data/sdel_curves.json [--sdel sdel.json] [--set key=value] --out DIR
//
// Writes DIR/sdel_curves.h5 (strain grid, damage and uniaxial stress per length) and DIR/summary.json
// (per length: initiation strain, strains at d+ = 0.1/0.5/0.9, peak stress, dissipated energy), and
// prints the summary table. Use it to inspect a fitted handoff before a 3D run, or the paper's.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sdel_curves.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/config.hpp"
#include "uhpc/hdf5_io.hpp"
#include "uhpc/logging.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/provenance.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace fs = std::filesystem;

namespace {

struct Settings {
  std::string sdel_file;
  std::vector<double> lengths_m;
  double strain_max = 0;
  int points = 0;
  double youngs_modulus_Pa = 0;
};

Settings read_settings(const uhpc::Config& cfg, const std::string& sdel_option) {
  Settings s;
  s.sdel_file = cfg.text("sdel_file");
  // A relative handoff path is relative to the config file, so shipped configs work from anywhere.
  if (fs::path(s.sdel_file).is_relative()) s.sdel_file = (fs::path(cfg.source()).parent_path() / s.sdel_file).string();
  if (!sdel_option.empty()) s.sdel_file = sdel_option;
  s.lengths_m = cfg.numbers("lengths_m", uhpc::Range::positive());
  s.strain_max = cfg.number("strain_max", uhpc::Range::open(0.0, 1.0));
  s.points = static_cast<int>(cfg.integer("points", uhpc::Range::closed(2, 1e6)));
  s.youngs_modulus_Pa = cfg.number("youngs_modulus_Pa", uhpc::Range::positive());
  cfg.finish();
  return s;
}

nlohmann::json summary_json(const uhpc::SdelLengthSummary& s) {
  return {{"length_m", s.length_m},
          {"lambda", s.lambda},
          {"initiation_strain", s.initiation_strain},
          {"damage_at_zero_strain", s.damage_at_zero_strain},
          {"strain_at_damage_0.1", s.strain_at_damage_10},
          {"strain_at_damage_0.5", s.strain_at_damage_50},
          {"strain_at_damage_0.9", s.strain_at_damage_90},
          {"peak_stress_Pa", s.peak_stress_Pa},
          {"strain_at_peak", s.strain_at_peak},
          {"dissipated_energy_J_m3", s.dissipated_energy_J_m3},
          {"crack_band_energy_J_m2", s.crack_band_energy_J_m2}};
}

int run(const std::string& config_path, const std::vector<std::string>& overrides, const std::string& sdel_option,
        const fs::path& out) {
  const uhpc::Config cfg = uhpc::Config::load(config_path, overrides);
  const Settings s = read_settings(cfg, sdel_option);
  const uhpc::OutputLock lock = uhpc::lock_output_directory(out, "uhpc-sdel");
  const uhpc::SdelHandoff handoff = uhpc::read_sdel_handoff(s.sdel_file);
  spdlog::info("SDEL from {} (a={}, A={}, nu={}, chi={})", s.sdel_file, handoff.constants.a, handoff.constants.A,
               handoff.constants.nu, handoff.constants.chi);

  std::vector<uhpc::SdelCurve> curves;
  for (double length : s.lengths_m)
    curves.push_back(uhpc::sdel_curve(handoff.constants, handoff.l_mac_m, length, s.strain_max, s.points,
                                      s.youngs_modulus_Pa));

  const uhpc::Provenance provenance = uhpc::Provenance::make("uhpc-sdel", cfg.hash());
  {
    uhpc::H5Writer h5(out / "sdel_curves.h5");
    const std::size_t n = curves.size(), m = static_cast<std::size_t>(s.points);
    std::vector<double> damage, stress;
    for (const auto& c : curves) {
      damage.insert(damage.end(), c.damage.begin(), c.damage.end());
      stress.insert(stress.end(), c.stress_Pa.begin(), c.stress_Pa.end());
    }
    h5.write("lengths", s.lengths_m, "m");
    h5.write("strain", curves.front().strain, "1");
    h5.write("damage", damage, {n, m}, "1");
    h5.write("stress", stress, {n, m}, "Pa");
    h5.set_attribute("", "sdel_file", s.sdel_file);
    h5.set_attribute("", "youngs_modulus_Pa", s.youngs_modulus_Pa);
    h5.write_provenance(provenance);
    h5.close();
  }

  nlohmann::json summary = {{"sdel_file", s.sdel_file},
                            {"constants",
                             {{"a", handoff.constants.a},
                              {"A", handoff.constants.A},
                              {"nu", handoff.constants.nu},
                              {"chi", handoff.constants.chi}}},
                            {"l_mac_m", handoff.l_mac_m},
                            {"youngs_modulus_Pa", s.youngs_modulus_Pa},
                            {"lengths", nlohmann::json::array()},
                            {"provenance", provenance.to_json()}};
  std::printf("%9s %12s %12s %12s %14s %14s %14s\n", "length_mm", "e_i", "e(d=0.5)", "e_peak", "peak_MPa",
              "g_J_m3", "G_band_J_m2");
  for (const auto& c : curves) {
    const auto& r = c.summary;
    summary["lengths"].push_back(summary_json(r));
    std::printf("%9.3f %12.4e %12.4e %12.4e %14.3f %14.1f %14.3f\n", r.length_m * 1e3, r.initiation_strain,
                r.strain_at_damage_50, r.strain_at_peak, r.peak_stress_Pa * 1e-6, r.dissipated_energy_J_m3,
                r.crack_band_energy_J_m2);
  }
  uhpc::write_text_atomic(out / "summary.json", summary.dump(2) + "\n");
  spdlog::info("wrote {} and {}", (out / "sdel_curves.h5").string(), (out / "summary.json").string());
  return uhpc::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Evaluates an SDEL handoff (sdel.json) at given length scales: damage and stress curves, "
               "strains at d+ = 0.1/0.5/0.9, peak stress, dissipated energy.",
               "uhpc-sdel"};
  std::string config_path, sdel_option, out;
  std::vector<std::string> overrides;
  app.add_option("--config", config_path, "settings (JSON), e.g. data/sdel_curves.json")->required();
  app.add_option("--sdel", sdel_option, "handoff file to evaluate (overrides the config's sdel_file)");
  app.add_option("--out", out, "output directory")->required();
  uhpc::add_set_option(app, overrides);
  return uhpc::run_main(app, [&] {
    app.parse(argc, argv);
    uhpc::init_logging("uhpc-sdel");
    return run(config_path, overrides, sdel_option, out);
  });
}
