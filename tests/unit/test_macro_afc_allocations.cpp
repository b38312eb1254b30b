// AfcMaterial::update allocates nothing (it runs inside the solver's particle loop): counted through
// the global operator new of this test program, over elastic, plastic, crushing and cracking steps,
// with both couplings of d+ (eq. 21's split and the cutoff), both tensile strain measures and both
// regularizations of the SDEL.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"

using uhpc::test::g_allocations;

namespace uhpc::macro {
namespace {

TEST(AfcAllocations, UpdateAllocatesNothing) {
  // Also with the crack band, whose reference curve is built when the law is made, not in a step.
  for (const SdelRegularization regularization : {SdelRegularization::Lambda, SdelRegularization::CrackBand})
  for (bool split : {false, true}) {
    AfcParams p = load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
    p.options.tensile_degradation = split ? TensileDegradation::Split : TensileDegradation::Cutoff;
    p.options.sdel_regularization = regularization;
    p.strain_measure = split ? TensileStrainMeasure::EffectiveTensile : TensileStrainMeasure::Mazars;
    const AfcMaterial law(p);
    AfcMaterial::State s;
    MaterialStep step;
    step.dt_s = 1e-7;
    step.spacing_m = 0.003;
    const long before = g_allocations.load();
    double ratio = 1.0;
    for (int i = 0; i < 2000; ++i) {
      // Compression with shear into crushing, then tension and shear to full cracking.
      const double sign = i < 1000 ? -1.0 : 1.0;
      step.strain_increment = Mat3::Zero();
      step.strain_increment(0, 0) = sign * 4e-5;
      step.strain_increment(0, 1) = step.strain_increment(1, 0) = 1e-5;
      ratio *= std::exp(-step.strain_increment.trace());
      step.density_ratio = ratio;
      law.update(s, step);
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << split;
    EXPECT_GT(s.mu_max, p.C7);
    EXPECT_EQ(s.d_plus, 1.0);
  }
}

}  // namespace
}  // namespace uhpc::macro
