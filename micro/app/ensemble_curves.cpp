#include "ensemble_curves.hpp"

#include <cmath>
#include <stdexcept>

namespace uhpc::micro {

std::vector<double> strain_grid(double max_strain, std::size_t points) {
  if (!(max_strain > 0.0) || !std::isfinite(max_strain) || points < 2)
    throw std::invalid_argument("strain_grid: needs max_strain > 0 and at least 2 points");
  std::vector<double> g(points);
  for (std::size_t j = 0; j < points; ++j)
    g[j] = max_strain * static_cast<double>(j) / static_cast<double>(points - 1);
  g.back() = max_strain;
  return g;
}

Spread spread(const std::vector<double>& v) {
  Spread s;
  s.count = v.size();
  if (v.empty()) return s;
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  if (v.size() < 2) return s;
  double ss = 0.0;  // two-pass: no cancellation for curves whose spread is small against the mean
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(ss / static_cast<double>(v.size() - 1));
  return s;
}

SizeCurves size_curves(double size_m, const std::vector<double>& grid, const std::vector<const ResampledCurve*>& cells) {
  const std::size_t m = grid.size();
  SizeCurves out;
  out.size_m = size_m;
  out.cells = cells.size();
  out.damage_mean.assign(m, 0.0);
  out.damage_std.assign(m, 0.0);
  out.stress_mean_Pa.assign(m, 0.0);
  out.stress_std_Pa.assign(m, 0.0);
  std::vector<double> d(cells.size()), s(cells.size());
  for (std::size_t j = 0; j < m; ++j) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c]->damage.size() != m || cells[c]->stress_Pa.size() != m)
        throw std::invalid_argument("size_curves: a cell's curve is not on the common grid");
      d[c] = cells[c]->damage[j];
      s[c] = cells[c]->stress_Pa[j];
    }
    const Spread sd = spread(d), sst = spread(s);
    out.damage_mean[j] = sd.mean;
    out.damage_std[j] = sd.std;
    out.stress_mean_Pa[j] = sst.mean;
    out.stress_std_Pa[j] = sst.std;
    if (sst.mean > out.nominal_strength_Pa) {
      out.nominal_strength_Pa = sst.mean;
      out.strain_at_nominal_strength = grid[j];
    }
  }
  return out;
}

Ensemble to_ensemble(const std::vector<double>& grid, const std::vector<SizeCurves>& sizes,
                     std::vector<double>* skipped) {
  Ensemble e;
  e.strain = grid;
  for (const SizeCurves& s : sizes) {
    if (s.cells == 0 || !(s.nominal_strength_Pa > 0.0)) {
      if (skipped) skipped->push_back(s.size_m);
      continue;
    }
    e.sizes_m.push_back(s.size_m);
    e.damage_mean.push_back(s.damage_mean);
    e.damage_std.push_back(s.damage_std);
    e.stress_mean_Pa.push_back(s.stress_mean_Pa);
    e.stress_std_Pa.push_back(s.stress_std_Pa);
    e.cells.push_back(static_cast<std::int64_t>(s.cells));
    e.nominal_strength_Pa.push_back(s.nominal_strength_Pa);
  }
  return e;
}

}  // namespace uhpc::micro
