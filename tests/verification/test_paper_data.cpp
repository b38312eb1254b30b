// The paper's data files (data/) against the check values of docs/specification.md. Every number checked here is computed
// from the files, never typed again; the printed value is only the expectation. "Within the printed
// digits" means within half a unit of the last printed place.
//
// The test also documents the inconsistencies of the paper's tables (listed in data/README.md): they
// are recorded, never "fixed" in the transcription.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "uhpc/csv.hpp"
#include "uhpc/sdel.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace {

const double kPi = std::acos(-1.0);

std::string data_path(const std::string& name) { return std::string(UHPC_DATA_DIR) + "/" + name; }

nlohmann::json load_json(const std::string& name) {
  std::ifstream in(data_path(name));
  if (!in) throw std::runtime_error("cannot open " + data_path(name));
  return nlohmann::json::parse(in);
}

uhpc::CsvTable table(const std::string& name) { return uhpc::CsvTable::read(data_path(name)); }

// A "parameter,value,unit" table as parameter -> {value, unit}.
struct Parameter {
  double value;
  std::string unit;
};
std::map<std::string, Parameter> parameters(const std::string& name) {
  const uhpc::CsvTable t = table(name);
  const auto names = t.text_column("parameter");
  const auto values = t.column("value");
  const auto units = t.text_column("unit");
  std::map<std::string, Parameter> out;
  for (std::size_t i = 0; i < t.rows(); ++i) out[names[i]] = {values[i], units[i]};
  return out;
}

// |computed - printed| <= half a unit of the last printed decimal place.
void expect_printed(double computed, double printed, int decimals, const std::string& what) {
  const double half_unit = 0.5 * std::pow(10.0, -decimals);
  EXPECT_LE(std::abs(computed - printed), half_unit * (1.0 + 1e-12))
      << what << ": computed " << computed << ", printed " << printed;
}

double bisect(const std::function<double(double)>& g, double lo, double hi) {
  if (g(lo) * g(hi) > 0.0) throw std::runtime_error("bisect: no sign change");
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(lo) * g(mid) <= 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// Composite Simpson rule on [a, b] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

// ---------------------------------------------------------------------------------------------------
// Burr XII pore sizes (Table 1, microstructure.json)

struct Burr {
  double k, alpha, beta, gamma;  // beta, gamma in m
  double cdf(double x) const {
    if (x <= gamma) return 0.0;
    return -std::expm1(-k * std::log1p(std::pow((x - gamma) / beta, alpha)));
  }
  double pdf(double x) const {
    if (x <= gamma) return 0.0;
    const double z = (x - gamma) / beta;
    return alpha * k / beta * std::pow(z, alpha - 1.0) * std::pow(1.0 + std::pow(z, alpha), -(k + 1.0));
  }
  double quantile(double u) const {
    return gamma + beta * std::pow(std::expm1(-std::log1p(-u) / k), 1.0 / alpha);
  }
  // E[X] = gamma + beta * integral_0^inf (1 + z^alpha)^-k dz, with z = t / (1 - t) mapping [0, inf)
  // to [0, 1); the integrand then vanishes like (1 - t)^(alpha k - 2) at t = 1.
  double mean_untruncated() const {
    const auto f = [&](double t) {
      if (t >= 1.0) return 0.0;
      const double z = t / (1.0 - t);
      return std::pow(1.0 + std::pow(z, alpha), -k) / ((1.0 - t) * (1.0 - t));
    };
    return gamma + beta * simpson(f, 0.0, 1.0, 200000);
  }
  // Closed form of the same: gamma + beta k B(k - 1/alpha, 1 + 1/alpha).
  double mean_closed_form() const {
    const double lb = std::lgamma(k - 1.0 / alpha) + std::lgamma(1.0 + 1.0 / alpha) - std::lgamma(k + 1.0);
    return gamma + beta * k * std::exp(lb);
  }
  // E[X | X < T] = gamma + integral_gamma^T (F(T) - F(x)) / F(T) dx.
  double mean_truncated(double T) const {
    const double FT = cdf(T);
    return gamma + simpson([&](double x) { return (FT - cdf(x)) / FT; }, gamma, T, 200000);
  }
  // E[X^2 | X < T], for the expected pore count per cell.
  double second_moment_truncated(double T) const {
    return simpson([&](double x) { return x * x * pdf(x); }, gamma, T, 400000) / cdf(T);
  }
};

Burr burr_from_file() {
  const nlohmann::json b = load_json("microstructure.json").at("burr");
  return {b.at("k").get<double>(), b.at("alpha").get<double>(), b.at("beta_m").get<double>(),
          b.at("gamma_m").get<double>()};
}

TEST(PaperData, Table1AgreesWithMicrostructureJson) {
  const auto p = parameters("table1_burr_pore_sizes.csv");
  const nlohmann::json m = load_json("microstructure.json");
  const nlohmann::json& b = m.at("burr");
  ASSERT_EQ(p.at("beta").unit, "um");
  ASSERT_EQ(p.at("gamma").unit, "um");
  ASSERT_EQ(p.at("fit_range_max").unit, "um");
  EXPECT_EQ(p.at("k").value, b.at("k").get<double>());
  EXPECT_EQ(p.at("alpha").value, b.at("alpha").get<double>());
  EXPECT_NEAR(p.at("beta").value * 1e-6, b.at("beta_m").get<double>(), 1e-15);
  EXPECT_NEAR(p.at("gamma").value * 1e-6, b.at("gamma_m").get<double>(), 1e-15);
  EXPECT_NEAR(p.at("fit_range_max").value * 1e-6, b.at("truncation_m").get<double>(), 1e-15);
  EXPECT_EQ(p.at("fit_range_min").value, p.at("gamma").value);  // the location is the fit's lower bound
  EXPECT_EQ(m.at("area_porosity").get<double>(), 0.034);
}

TEST(PaperData, BurrCheckValuesReferToTheUntruncatedDistribution) {
  // docs/specification.md: mean 184.3 um, median 148.1 um, 90th percentile 316.0 um, P(ESD < 600 um) = 0.9865.
  // All four are statistics of the UNTRUNCATED Burr distribution: truncated at the fit's upper
  // bound (1.3 mm) the mean is 183.3 um, the median 148.0 um, the 90th percentile 315.3 um and
  // P(< 600 um) = 0.9872, none of which matches the printed digits.
  const Burr burr = burr_from_file();
  const double T = load_json("microstructure.json").at("burr").at("truncation_m").get<double>();
  const double um = 1e-6;

  const double mean = burr.mean_untruncated();
  EXPECT_NEAR(mean, burr.mean_closed_form(), 1e-6 * mean);  // quadrature against the closed form
  expect_printed(mean / um, 184.3, 1, "untruncated mean [um]");
  expect_printed(burr.quantile(0.5) / um, 148.1, 1, "median [um]");
  expect_printed(burr.quantile(0.9) / um, 316.0, 1, "90th percentile [um]");
  expect_printed(burr.cdf(600 * um), 0.9865, 4, "P(ESD < 600 um)");
  EXPECT_NEAR(burr.cdf(burr.quantile(0.9)), 0.9, 1e-12);

  // The truncated statistics, to show that they do not match.
  const double FT = burr.cdf(T);
  EXPECT_GT(std::abs(burr.mean_truncated(T) / um - 184.3), 0.5);
  EXPECT_GT(std::abs(burr.quantile(0.5 * FT) / um - 148.1), 0.05);
  EXPECT_GT(std::abs(burr.quantile(0.9 * FT) / um - 316.0), 0.5);
  EXPECT_GT(std::abs(burr.cdf(600 * um) / FT - 0.9865), 0.0005);
}

TEST(PaperData, ExpectedPoreCountsPerCellUseTheTruncatedDistribution) {
  // docs/physics.md section 1: about 8, 19, 23, 39 pores per cell at 3.4 % area porosity. These follow
  // from E[pi D^2 / 4] of the distribution truncated at 1.3 mm (8.3, 18.7, 23.1, 39.0); untruncated
  // they would be 8.0, 17.9, 22.1, 37.3.
  const nlohmann::json m = load_json("microstructure.json");
  const Burr burr = burr_from_file();
  const double T = m.at("burr").at("truncation_m").get<double>();
  const double phi = m.at("area_porosity").get<double>();
  const double mean_area = kPi / 4.0 * burr.second_moment_truncated(T);
  const std::vector<double> sizes = m.at("cell_sizes_m").get<std::vector<double>>();
  const std::vector<double> expected = {8, 19, 23, 39};
  ASSERT_EQ(sizes.size(), expected.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(std::round(phi * sizes[i] * sizes[i] / mean_area), expected[i]) << "cell " << sizes[i];
  }
}

// ---------------------------------------------------------------------------------------------------
// Microcell matrix (Table 2)

TEST(PaperData, Table2DerivedLengths) {
  const auto p = parameters("table2_microcell_matrix.csv");
  const nlohmann::json mat = load_json("microstructure.json").at("matrix");
  const double E = mat.at("youngs_modulus_Pa").get<double>();
  const double ft = mat.at("tensile_strength_Pa").get<double>();
  const double Gf = mat.at("fracture_energy_J_m2").get<double>();
  ASSERT_EQ(p.at("youngs_modulus").unit, "MPa");
  ASSERT_EQ(p.at("tensile_strength").unit, "MPa");
  ASSERT_EQ(p.at("fracture_energy").unit, "N/m");
  EXPECT_NEAR(p.at("youngs_modulus").value * 1e6, E, 1e-6);
  EXPECT_NEAR(p.at("tensile_strength").value * 1e6, ft, 1e-6);
  EXPECT_EQ(p.at("fracture_energy").value, Gf);
  EXPECT_EQ(p.at("poissons_ratio").value, mat.at("poissons_ratio").get<double>());

  expect_printed(2.0 * Gf / ft / 1e-6, 3.08, 2, "w_c = 2 G_f / f_t [um]");
  expect_printed(E * Gf / (ft * ft) / 1e-3, 3.01, 2, "l_ch = E G_f / f_t^2 [mm]");
}

// ---------------------------------------------------------------------------------------------------
// SDEL (Table 4, sdel_paper.json)

TEST(PaperData, Table4AgreesWithSdelPaperJsonAndGivesTheCheckStrains) {
  const auto p = parameters("table4_sdel_constants.csv");
  const uhpc::SdelHandoff h = uhpc::read_sdel_handoff(data_path("sdel_paper.json"));
  EXPECT_EQ(p.at("a").value, h.constants.a);
  EXPECT_EQ(p.at("A").value, h.constants.A);
  EXPECT_EQ(p.at("nu").value, h.constants.nu);
  EXPECT_EQ(p.at("chi").value, h.constants.chi);
  EXPECT_EQ(h.cell_sizes_m, load_json("microstructure.json").at("cell_sizes_m").get<std::vector<double>>());
  EXPECT_EQ(h.l_mac_m, load_json("microstructure.json").at("l_mac_m").get<double>());

  // docs/specification.md: d+ = 0.5 at 3.58e-4 (l_mic = 3.0 mm) and 2.71e-4 (6.5 mm).
  const double e3 = uhpc::sdel_strain_at_damage(uhpc::sdel_lambda(h.cell_sizes_m.front(), h.l_mac_m), 0.5, h.constants);
  const double e65 = uhpc::sdel_strain_at_damage(uhpc::sdel_lambda(h.cell_sizes_m.back(), h.l_mac_m), 0.5, h.constants);
  expect_printed(e3 * 1e4, 3.58, 2, "strain at d = 0.5, 3.0 mm [1e-4]");
  expect_printed(e65 * 1e4, 2.71, 2, "strain at d = 0.5, 6.5 mm [1e-4]");
}

// ---------------------------------------------------------------------------------------------------
// AFC constants (Table 6, afc_uhpc.json)

struct Afc {
  double rho, G, C1, C2, C3, C4, C5, C6, C7, C8, C9, K1, K2, K3, D1, An, Tmax, rate0;
};

Afc afc_from_file() {
  const nlohmann::json j = load_json("afc_uhpc.json");
  const auto n = [&](const char* key) { return j.at(key).get<double>(); };
  return {n("density_kg_m3"), n("shear_modulus_Pa"), n("C1_Pa"), n("C2_Pa"), n("C3"), n("C4"),
          n("C5_Pa"), n("C6_Pa"), n("C7"), n("C8_Pa"), n("C9"), n("K1_Pa"), n("K2_Pa"), n("K3_Pa"),
          n("D1_1_Pa"), n("An_1_Pa"), n("Tmax_Pa"), n("reference_strain_rate_1_s")};
}

TEST(PaperData, Table6AgreesWithAfcJson) {
  // Every Table 6 row converted from its printed unit to SI equals the JSON value.
  const auto p = parameters("table6_afc_constants.csv");
  const nlohmann::json j = load_json("afc_uhpc.json");
  const std::map<std::string, std::string> key = {
      {"density", "density_kg_m3"}, {"shear_modulus", "shear_modulus_Pa"}, {"C1", "C1_Pa"}, {"C2", "C2_Pa"},
      {"C3", "C3"}, {"C4", "C4"}, {"C5", "C5_Pa"}, {"C6", "C6_Pa"}, {"C7", "C7"}, {"C8", "C8_Pa"},
      {"C9", "C9"}, {"K1", "K1_Pa"}, {"K2", "K2_Pa"}, {"K3", "K3_Pa"}, {"D1", "D1_1_Pa"},
      {"An", "An_1_Pa"}, {"Tmax", "Tmax_Pa"}};
  const std::map<std::string, double> to_si = {{"MPa", 1e6}, {"1/MPa", 1e-6}, {"-", 1.0}, {"kg/m3", 1.0}};
  ASSERT_EQ(p.size(), key.size());
  for (const auto& [name, param] : p) {
    ASSERT_TRUE(key.count(name)) << name;
    ASSERT_TRUE(to_si.count(param.unit)) << name << " unit " << param.unit;
    const double si = param.value * to_si.at(param.unit);
    EXPECT_NEAR(si, j.at(key.at(name)).get<double>(), 1e-12 * std::abs(si)) << name;
  }
  EXPECT_EQ(j.at("reference_strain_rate_1_s").get<double>(), 1e-4);
}

TEST(PaperData, AfcCheckValues) {
  const Afc m = afc_from_file();
  const double MPa = 1e6;
  const double K = m.C6 / m.C7;  // elastic bulk modulus of the hydrostat
  const double E = 9.0 * K * m.G / (3.0 * K + m.G);
  expect_printed(K / MPa, 22070.0, 0, "K_e = C6 / C7 [MPa]");
  // "43 300 MPa": the trailing zeros are not significant (computed 43 300.6), so three digits.
  EXPECT_NEAR(E / MPa, 43300.0, 50.0);

  const double x = m.C9 - m.C7;
  expect_printed((m.C6 + m.K1 * x + m.K2 * x * x + m.K3 * x * x * x) / MPa, 807.7, 1, "P(C9) [MPa]");
  expect_printed(std::sqrt((K + 4.0 * m.G / 3.0) / m.rho), 4274.0, 0, "dilatational wave speed [m/s]");

  // Eq. (33), unconfined compression: P = q/3, d- = 0, rate factor 1 -> q = S(q/3).
  const auto S_comp = [&](double P) { return m.C1 - m.C2 * std::exp(-m.An * P) + m.C4 * P; };
  const double fc = bisect([&](double q) { return q - S_comp(q / 3.0); }, 0.0, 1e9);
  expect_printed(fc / MPa, 193.6, 1, "unconfined compressive strength, eq. 33 [MPa]");
  // (The measured unconfined compressive strength is 210 MPa; eq. 33 gives 8 % less.)

  // Eq. (35), uniaxial tension: P = -q/3, d+ = d- = 0, rate factor 1 -> q = S(-q/3).
  const auto S_tens = [&](double P) { return (m.C1 - m.C2) * (m.Tmax + P) / m.Tmax; };
  const double ft = bisect([&](double q) { return q - S_tens(-q / 3.0); }, 0.0, 3.0 * m.Tmax);
  expect_printed(ft / MPa, 15.9, 1, "uniaxial tensile strength, eq. 35 [MPa]");
}

// ---------------------------------------------------------------------------------------------------
// Ballistic experiments and the paper's simulations (Tables 5, 7, 8)

struct Shots {
  std::vector<double> v0, vr, dv, ke;
};

Shots shots(const std::string& name) {
  const uhpc::CsvTable t = table(name);
  EXPECT_EQ(t.unit("impact_velocity"), "m/s");
  EXPECT_EQ(t.unit("ke_reduction"), "J");
  return {t.column("impact_velocity"), t.column("residual_velocity"), t.column("velocity_reduction"),
          t.column("ke_reduction")};
}

double projectile_mass() { return load_json("projectile.json").at("mass_kg").get<double>(); }

// The mass of a steel sphere of the projectile's diameter and density.
double sphere_mass() {
  const nlohmann::json p = load_json("projectile.json");
  const double d = p.at("diameter_m").get<double>();
  return p.at("density_kg_m3").get<double>() * kPi * d * d * d / 6.0;
}

TEST(PaperData, Table7VelocityReductionsAndTable5Velocities) {
  const uhpc::CsvTable t5 = table("table5_ballistic_experiments.csv");
  const Shots e = shots("table7_experimental_reductions.csv");
  EXPECT_EQ(t5.column("impact_velocity"), e.v0);
  EXPECT_EQ(t5.column("residual_velocity"), e.vr);
  for (std::size_t i = 0; i < e.v0.size(); ++i) EXPECT_EQ(e.dv[i], e.v0[i] - e.vr[i]) << "row " << i + 1;
  const Shots s = shots("table8_paper_simulations.csv");
  for (std::size_t i = 0; i < s.v0.size(); ++i) EXPECT_EQ(s.dv[i], s.v0[i] - s.vr[i]) << "row " << i + 1;
}

TEST(PaperData, KineticEnergyReductionsUseA842GramSphereNotTheStated9071Grams) {
  // Tables 7 and 8 print KE reductions that are NOT 1/2 m (v0^2 - vr^2) with the stated projectile
  // mass m = 9.071 g (610 -> 53 m/s would give 1675 J, printed 1555 J). They are reproduced by
  // m = 8.42 g, the mass of a 12.7 mm steel sphere at 7850 kg/m3: the paper computed them from the
  // nominal sphere, not from the weighed projectile. Transcribed as printed; see data/README.md.
  const double m_stated = projectile_mass();
  const double m_sphere = sphere_mass();
  EXPECT_NEAR(m_sphere * 1e3, 8.42, 0.005);
  for (const char* name : {"table7_experimental_reductions.csv", "table8_paper_simulations.csv"}) {
    const Shots s = shots(name);
    for (std::size_t i = 0; i < s.v0.size(); ++i) {
      const double dv2 = s.v0[i] * s.v0[i] - s.vr[i] * s.vr[i];
      const double with_stated = 0.5 * m_stated * dv2;
      const double with_sphere = 0.5 * m_sphere * dv2;
      EXPECT_GT(std::abs(with_stated - s.ke[i]) / s.ke[i], 0.05) << name << " row " << i + 1;
      EXPECT_LT(std::abs(with_sphere - s.ke[i]) / s.ke[i], 0.01) << name << " row " << i + 1;
      // The mass each printed row implies: 8.42 g to within the rounding of the printed joules.
      EXPECT_NEAR(2.0 * s.ke[i] / dv2 * 1e3, 8.42, 0.005) << name << " row " << i + 1;
    }
  }
  const Shots e = shots("table7_experimental_reductions.csv");
  EXPECT_NEAR(0.5 * m_stated * (e.v0[0] * e.v0[0] - e.vr[0] * e.vr[0]), 1675.0, 0.5);
}

TEST(PaperData, Table8RmsResidualVelocityError) {
  // docs/specification.md: RMS of (paper residual - experiment residual) over the 7 rows = 35.6 m/s; the rows pair
  // with Table 7 by order (the paper's "analogous experiment").
  const Shots s = shots("table8_paper_simulations.csv");
  const Shots e = shots("table7_experimental_reductions.csv");
  ASSERT_EQ(s.vr.size(), 7u);
  ASSERT_EQ(e.vr.size(), 7u);
  double sum = 0.0;
  for (std::size_t i = 0; i < 7; ++i) sum += (s.vr[i] - e.vr[i]) * (s.vr[i] - e.vr[i]);
  expect_printed(std::sqrt(sum / 7.0), 35.6, 1, "RMS residual velocity error [m/s]");
}

TEST(PaperData, Table8PercentErrorsAreExperimentMinusSimulation) {
  // The printed % errors are (experiment - simulation) / experiment x 100, rounded to integers: a
  // positive error means the simulation UNDER-predicts the reduction (the opposite of the usual
  // "simulation - reference" sign). All 14 printed values agree with that convention.
  const uhpc::CsvTable t8 = table("table8_paper_simulations.csv");
  const Shots s = shots("table8_paper_simulations.csv");
  const Shots e = shots("table7_experimental_reductions.csv");
  const std::vector<double> dv_err = t8.column("velocity_reduction_error");
  const std::vector<double> ke_err = t8.column("ke_reduction_error");
  EXPECT_EQ(t8.unit("velocity_reduction_error"), "%");
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(std::round(100.0 * (e.dv[i] - s.dv[i]) / e.dv[i]), dv_err[i]) << "row " << i + 1;
    EXPECT_EQ(std::round(100.0 * (e.ke[i] - s.ke[i]) / e.ke[i]), ke_err[i]) << "row " << i + 1;
  }
  // docs/specification.md: velocity-reduction errors within -9 % .. +8 %, KE-reduction errors within -5 % .. +2 %.
  EXPECT_EQ(*std::min_element(dv_err.begin(), dv_err.end()), -9.0);
  EXPECT_EQ(*std::max_element(dv_err.begin(), dv_err.end()), 8.0);
  EXPECT_EQ(*std::min_element(ke_err.begin(), ke_err.end()), -5.0);
  EXPECT_EQ(*std::max_element(ke_err.begin(), ke_err.end()), 2.0);
}

TEST(PaperData, Table8ImpactVelocitiesAreOnTheSimulationGrid) {
  // The 81 runs go from 400 to 1200 m/s in 10 m/s steps; each Table 8 row is the grid velocity
  // nearest to its experiment (613 m/s is compared with the 610 m/s run).
  const Shots s = shots("table8_paper_simulations.csv");
  const Shots e = shots("table7_experimental_reductions.csv");
  for (std::size_t i = 0; i < s.v0.size(); ++i) {
    EXPECT_EQ(std::fmod(s.v0[i], 10.0), 0.0);
    EXPECT_GE(s.v0[i], 400.0);
    EXPECT_LE(s.v0[i], 1200.0);
    EXPECT_LE(std::abs(s.v0[i] - e.v0[i]), 5.0) << "row " << i + 1;
  }
}

TEST(PaperData, Table5TargetMassesAndThicknesses) {
  const uhpc::CsvTable t5 = table("table5_ballistic_experiments.csv");
  ASSERT_EQ(t5.unit("thickness"), "mm");
  ASSERT_EQ(t5.unit("target_mass"), "kg");
  const std::vector<double> t = t5.column("thickness");
  const std::vector<double> mass = t5.column("target_mass");
  const double diameter = load_json("microstructure.json").at("l_mac_m").get<double>();  // panel diameter
  const double rho = afc_from_file().rho;
  // The printed target masses equal pi (D/2)^2 t rho with the AFC density 2555.7 kg/m3 to within
  // 0.03 %: they are consistent with the thicknesses (and were probably computed from them).
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double computed = kPi * 0.25 * diameter * diameter * t[i] * 1e-3 * rho;
    EXPECT_NEAR(computed, mass[i], 5e-4 * mass[i]) << "row " << i + 1;
  }
  // The text calls 31.75 mm the AVERAGE thickness (Tables 7 and 8 list it as nominal), but the mean
  // of the seven measured thicknesses is 30.78 mm, 3 % thinner. Recorded, not corrected.
  double mean = 0.0;
  for (const double x : t) mean += x / static_cast<double>(t.size());
  expect_printed(mean, 30.78, 2, "mean Table 5 thickness [mm]");
  const std::vector<double> nominal = table("table7_experimental_reductions.csv").column("nominal_thickness");
  for (const double n : nominal) EXPECT_EQ(n, 31.75);
  EXPECT_GT(std::abs(mean - nominal.front()), 0.9);
}

}  // namespace
