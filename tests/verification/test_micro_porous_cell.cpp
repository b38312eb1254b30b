// A porous Burr cell's crack analysis end to end through `uhpc-micro run` (the shipped micro_run.json,
// 3.0 mm, 100 um), checked against the conservation law and the bridging identity rather than against
// a figure: the work done equals stored + dissipated energy, d_energy = d_force (Hill-Mandel), and the
// path stays in tension. The seed is a cell whose crack growth once landed it in compression (e = -2.3e-4
// at -9.6 MPa in one step), which was then taken as separation. About a minute.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fracture_analyzer.hpp"
#include "run_commands.hpp"
#include "test_support.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/hdf5_io.hpp"

namespace uhpc::micro {
namespace {

class MicroPorousCell : public test::ScratchDirTest {};

TEST_F(MicroPorousCell, GrowthNeverCrossesIntoCompressionAndEnergyBalances) {
  const std::vector<std::string> sets = {"cell.cell_size_m=0.003", "cell.seed=3360460126177276",
                                         "cell.discretization.nominal_spacing_m=1e-4"};
  ASSERT_EQ(run_main("uhpc-micro run", [&] {
              return run_cell_command(std::string(UHPC_DATA_DIR) + "/micro_run.json", sets, dir_, fracture_analyzer_factory());
            }),
            0);
  std::ifstream in(dir_ / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  EXPECT_EQ(s["diagnostic"], "reached max_strain");
  EXPECT_LT(std::abs(s["energy_balance_relative"].get<double>()), 0.02);
  // The bridging identity d_energy = d_force holds to the solver's equilibrium tolerance: 3.9e-7 measured.
  // The bound is this test's own (the shipped micro_run.json's bridging.tolerance, 1e-2, is a setting a
  // user may change, and 25 000 times the measured value); 1e-5 leaves 25 times the measured value.
  const double bridging = s["bridging"]["max_abs_difference"].get<double>();
  std::printf("bridging: max |d_energy - d_force| = %.3e\n", bridging);
  EXPECT_LT(bridging, 1e-5) << s["bridging"].dump();
  EXPECT_LT(s["operator_energy_mismatch"].get<double>(), 0.01);
  const H5Reader h5(dir_ / "curves.h5");
  const std::vector<double> strain = h5.read_doubles("states/strain").values;
  const std::vector<double> stress = h5.read_doubles("states/sigma_bar").values;
  ASSERT_EQ(strain.size(), stress.size());
  for (std::size_t i = 0; i < strain.size(); ++i) {
    EXPECT_GE(strain[i], 0.0) << "state " << i;
    EXPECT_GE(stress[i], 0.0) << "state " << i;
  }
}

}  // namespace
}  // namespace uhpc::micro
