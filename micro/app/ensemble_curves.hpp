#pragma once
// Ensemble statistics of the cells' curves (docs/physics.md section 2, "Ensemble"): per size, the mean and
// the spread over the cells of the stress and the damage on the common strain grid, and the nominal
// strength (the peak of the mean stress curve, the size effect law's sigma_N). Pure functions, no I/O;
// the result converts to the ensemble.h5 contract (uhpc/ensemble_file.hpp).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "energy_bridging.hpp"
#include "uhpc/ensemble_file.hpp"

namespace uhpc::micro {

// A common strain grid: `points` strains evenly spaced over [0, max_strain] (strictly ascending).
std::vector<double> strain_grid(double max_strain, std::size_t points);

// Mean and [choice] sample standard deviation (n - 1 in the denominator: the cells are a sample of the
// population, and calibrate divides by sqrt(cells) for the standard error of the mean); 0 for n < 2.
struct Spread {
  double mean = 0.0;
  double std = 0.0;
  std::size_t count = 0;
};
Spread spread(const std::vector<double>& values);

struct SizeCurves {
  double size_m = 0.0;
  std::vector<double> damage_mean, damage_std, stress_mean_Pa, stress_std_Pa;
  std::size_t cells = 0;              // cells averaged
  double nominal_strength_Pa = 0.0;   // max of stress_mean_Pa
  double strain_at_nominal_strength = 0.0;
};

// Statistics over the given cells' resampled curves (all on `grid`). The
// caller decides which cells count (failed and incomplete cells are excluded before this); no cells
// gives zero curves and cells = 0.
SizeCurves size_curves(double size_m, const std::vector<double>& grid, const std::vector<const ResampledCurve*>& cells);

// The ensemble file's content for the sizes that have at least one cell (the contract needs
// cells >= 1 and a positive nominal strength); `skipped` receives the sizes left out.
Ensemble to_ensemble(const std::vector<double>& grid, const std::vector<SizeCurves>& sizes,
                     std::vector<double>* skipped = nullptr);

}  // namespace uhpc::micro
