#pragma once
// The settings of uhpc-calibrate (data/calibrate.json) and of its `synthesize` subcommand
// (data/synthetic_ensemble.json), read through uhpc::Config: every key required, unknown keys errors.
// The keys and their meaning are listed in calibrate/README.md.
#include <string>

#include "sdel_fit.hpp"
#include "synthetic_ensemble.hpp"
#include "uhpc/config.hpp"

namespace uhpc {

struct CalibrateSettings {
  double l_mac_m = 0.4064;           // lambda = l_mic / l_mac
  double f_t_Pa = 22.7e6;            // reference strength of the size effect law (Table 2 matrix)
  std::string strain_measure;        // written into the handoff
  int figure_points = 201;           // sizes at which the fitted size effect law is tabulated (Fig. 10)
  SdelFitOptions fit;
};

CalibrateSettings read_calibrate_settings(const Config& cfg);

// l_mac_m is not in the synthesize config: it comes from the handoff the curves are made from.
SyntheticEnsembleSettings read_synthetic_settings(const Config& cfg, double l_mac_m);

}  // namespace uhpc
