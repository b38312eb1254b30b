#pragma once
// Statistics of the generated cells of one size: pore counts, largest pores, achieved porosity, node
// counts, and the pore-size histogram against the truncated Burr pdf (placed pores and all draws).
#include <cstddef>
#include <vector>

#include "burr.hpp"
#include "cell_generator.hpp"
#include "cell_mesh.hpp"

namespace uhpc::micro {

struct Spread {
  double mean = 0.0, min = 0.0, max = 0.0, stddev = 0.0;
};
Spread spread_of(const std::vector<double>& values);

struct HistogramBin {
  double lo_m = 0.0, hi_m = 0.0;
  std::size_t drawn = 0, placed = 0;
  double drawn_density_1_m = 0.0, placed_density_1_m = 0.0;  // count / (total x bin width)
  double burr_density_1_m = 0.0;                              // (F(hi) - F(lo)) / width, truncated law
};

struct SizeStatistics {
  double side_m = 0.0;
  std::size_t cells = 0;
  Spread pore_count, largest_pore_m, porosity, node_count, triangle_count;
  // Expected pore count of a cell at the target porosity: phi l^2 / (pi/4 E[D^2]), truncated law.
  double expected_pore_count = 0.0;
  std::size_t drawn = 0, placed = 0;
  double ks_drawn = 0.0, ks_drawn_p = 0.0;    // all draws against the truncated law
  double ks_placed = 0.0, ks_placed_p = 0.0;  // placed pores (biased small by the porosity budget)
  std::vector<HistogramBin> histogram;
};

// `meshes` may be empty (no discretization) or hold one entry per cell.
SizeStatistics size_statistics(const std::vector<GeneratedCell>& cells, const std::vector<CellDiscretization>& meshes,
                               const BurrXII& burr, double porosity_target, int bins);

}  // namespace uhpc::micro
