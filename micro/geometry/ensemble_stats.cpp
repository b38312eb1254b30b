#include "ensemble_stats.hpp"

#include <algorithm>
#include <cmath>

#include "ks_test.hpp"

namespace uhpc::micro {

Spread spread_of(const std::vector<double>& v) {
  Spread s;
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.stddev += (x - s.mean) * (x - s.mean);
  s.stddev = v.size() > 1 ? std::sqrt(s.stddev / static_cast<double>(v.size() - 1)) : 0.0;
  return s;
}

SizeStatistics size_statistics(const std::vector<GeneratedCell>& cells, const std::vector<CellDiscretization>& meshes,
                               const BurrXII& burr, double porosity_target, int bins) {
  SizeStatistics st;
  st.cells = cells.size();
  if (cells.empty()) return st;
  st.side_m = cells.front().geometry.side_m;
  std::vector<double> counts, largest, porosity, nodes, triangles, drawn, placed;
  for (const GeneratedCell& c : cells) {
    counts.push_back(static_cast<double>(c.geometry.pores.size()));
    double big = 0.0;
    for (const Pore& p : c.geometry.pores) {
      big = std::max(big, p.diameter_m);
      placed.push_back(p.diameter_m);
    }
    largest.push_back(big);
    porosity.push_back(c.geometry.porosity());
    drawn.insert(drawn.end(), c.record.drawn_diameters_m.begin(), c.record.drawn_diameters_m.end());
  }
  for (const CellDiscretization& m : meshes) {
    nodes.push_back(static_cast<double>(m.node_count()));
    triangles.push_back(static_cast<double>(m.triangle_count()));
  }
  st.pore_count = spread_of(counts);
  st.largest_pore_m = spread_of(largest);
  st.porosity = spread_of(porosity);
  st.node_count = spread_of(nodes);
  st.triangle_count = spread_of(triangles);
  st.expected_pore_count = porosity_target * st.side_m * st.side_m / (0.25 * M_PI * burr.mean_square());
  st.drawn = drawn.size();
  st.placed = placed.size();
  auto cdf = [&](double x) { return burr.cdf(x); };
  st.ks_drawn = ks_statistic(drawn, cdf);
  st.ks_drawn_p = ks_p_value(st.ks_drawn, drawn.size());
  st.ks_placed = ks_statistic(placed, cdf);
  st.ks_placed_p = ks_p_value(st.ks_placed, placed.size());

  // Linear bins over the law's support [gamma, truncation].
  const double lo = burr.parameters().gamma_m, hi = burr.truncation_m(), width = (hi - lo) / bins;
  st.histogram.resize(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) {
    HistogramBin& bin = st.histogram[static_cast<std::size_t>(b)];
    bin.lo_m = lo + b * width;
    bin.hi_m = b + 1 == bins ? hi : lo + (b + 1) * width;
    bin.burr_density_1_m = (burr.cdf(bin.hi_m) - burr.cdf(bin.lo_m)) / (bin.hi_m - bin.lo_m);
  }
  auto bin_of = [&](double x) {
    return std::min(static_cast<std::size_t>(std::max(0.0, (x - lo) / width)), st.histogram.size() - 1);
  };
  for (double x : drawn) ++st.histogram[bin_of(x)].drawn;
  for (double x : placed) ++st.histogram[bin_of(x)].placed;
  for (HistogramBin& bin : st.histogram) {
    const double w = bin.hi_m - bin.lo_m;
    bin.drawn_density_1_m = drawn.empty() ? 0.0 : bin.drawn / (static_cast<double>(drawn.size()) * w);
    bin.placed_density_1_m = placed.empty() ? 0.0 : bin.placed / (static_cast<double>(placed.size()) * w);
  }
  return st;
}

}  // namespace uhpc::micro
