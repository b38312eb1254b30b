#include "cell_generator.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fmt/format.h>

namespace uhpc::micro {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Rectangle = Kernel::Iso_rectangle_2;

double disk_area(double d) { return 0.25 * M_PI * d * d; }

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// Pore diameters (unsorted) whose total area lands in the porosity band (docs/physics.md [choice]): a draw
// that would overshoot the band, or that cannot fit in the cell with its ligaments, is rejected.
std::vector<double> draw_diameters(const CellOptions& o, const BurrXII& burr, std::mt19937_64& rng,
                                   GenerationRecord& record) {
  const double cell_area = o.side_m * o.side_m;
  const double target = o.porosity.target * cell_area, tolerance = o.porosity.tolerance * cell_area;
  const double largest_fitting = o.side_m - 2.0 * o.placement.min_ligament_m;
  std::vector<double> accepted;
  double area = 0.0;
  while (area < target - tolerance) {
    if (static_cast<long long>(record.drawn_diameters_m.size()) >= o.porosity.max_draws)
      throw CellGenerationError(
          CellGenerationError::Reason::UnreachablePorosity,
          fmt::format("porosity {:g} not reached within {:g} after {} draws (reached {:.5f})", o.porosity.target,
                      o.porosity.tolerance, o.porosity.max_draws, area / cell_area));
    const double d = burr.sample(rng);
    record.drawn_diameters_m.push_back(d);
    if (area + disk_area(d) > target + tolerance || d > largest_fitting) {
      ++record.rejected_draws;
      continue;
    }
    accepted.push_back(d);
    area += disk_area(d);
  }
  return accepted;
}

// Random sequential addition, largest first: each pore gets uniform random centres in the part of the
// cell that keeps the edge ligament until one keeps the ligament to every placed pore. The tests are
// CGAL predicates, exact for the given doubles, so the accept/reject decisions (and thus the cell) do
// not depend on rounding in the distance computation.
std::vector<Pore> place_pores(std::vector<double> diameters, const CellOptions& o, std::mt19937_64& rng,
                              GenerationRecord& record) {
  std::stable_sort(diameters.begin(), diameters.end(), std::greater<double>());
  const double lig = o.placement.min_ligament_m;
  std::vector<Pore> placed;
  for (std::size_t i = 0; i < diameters.size(); ++i) {
    const double r = 0.5 * diameters[i];
    const double lo = r + lig, hi = o.side_m - r - lig;
    const Rectangle allowed(Point(lo, lo), Point(hi, hi));
    bool ok = false;
    for (long long attempt = 0; attempt < o.placement.max_attempts_per_pore && !ok; ++attempt) {
      ++record.placement_attempts;
      const Point c(lo + (hi - lo) * uniform01(rng), lo + (hi - lo) * uniform01(rng));
      if (allowed.has_on_unbounded_side(c)) continue;  // only by rounding at hi
      ok = std::none_of(placed.begin(), placed.end(), [&](const Pore& q) {
        const double reach = r + q.radius_m() + lig;
        return CGAL::compare_squared_distance(c, Point(q.center_m.x, q.center_m.y), reach * reach) == CGAL::SMALLER;
      });
      if (ok) placed.push_back(Pore{{c.x(), c.y()}, diameters[i]});
    }
    if (!ok)
      throw CellGenerationError(
          CellGenerationError::Reason::PlacementFailed,
          fmt::format("pore {} of {} (diameter {:.1f} um) could not be placed after {} attempts with a ligament of "
                      "{:.1f} um",
                      i + 1, diameters.size(), diameters[i] * 1e6, o.placement.max_attempts_per_pore, lig * 1e6));
  }
  return placed;
}

std::vector<CrackSeed> make_seeds(const std::vector<Pore>& pores, const CellOptions& o, std::mt19937_64& rng) {
  const Vec2 n = load_normal(o.load);
  const double c = std::cos(o.seeds.tilt_rad), s = std::sin(o.seeds.tilt_rad);
  std::vector<CrackSeed> seeds;
  for (std::size_t p = 0; p < pores.size(); ++p) {
    std::vector<double> sides;
    if (o.seeds.per_pore == 2) sides = {1.0, -1.0};
    if (o.seeds.per_pore == 1) sides = {uniform01(rng) < 0.5 ? 1.0 : -1.0};
    for (double side : sides) {
      const Vec2 out{side * n.x, side * n.y};
      const Vec2 dir{c * out.x - s * out.y, s * out.x + c * out.y};
      const Pore& q = pores[p];
      const Vec2 root{q.center_m.x + q.radius_m() * out.x, q.center_m.y + q.radius_m() * out.y};
      seeds.push_back(CrackSeed{static_cast<int>(p), root,
                                {root.x + o.seeds.length_m * dir.x, root.y + o.seeds.length_m * dir.y}});
    }
  }
  return seeds;
}

}  // namespace

Vec2 load_normal(LoadAxis load) { return load == LoadAxis::X ? Vec2{0.0, 1.0} : Vec2{1.0, 0.0}; }

void check_cell_options(const CellOptions& o) {
  using R = CellGenerationError::Reason;
  const double gamma = o.burr.gamma_m, lig = o.placement.min_ligament_m;
  if (o.side_m < gamma + 2.0 * lig)
    throw CellGenerationError(R::CellTooSmall,
                              fmt::format("cell side {:g} m cannot hold the smallest pore ({:g} m) with two ligaments "
                                          "of {:g} m",
                                          o.side_m, gamma, lig));
  const double cell_area = o.side_m * o.side_m;
  if (disk_area(gamma) > (o.porosity.target + o.porosity.tolerance) * cell_area)
    throw CellGenerationError(R::UnreachablePorosity,
                              fmt::format("porosity {:g} +- {:g} is unreachable: one smallest pore ({:g} m) alone "
                                          "gives {:.5f}",
                                          o.porosity.target, o.porosity.tolerance, gamma, disk_area(gamma) / cell_area));
  if (o.porosity.tolerance <= 0.0 || o.porosity.tolerance >= o.porosity.target)
    throw CellGenerationError(R::BadOption, "porosity tolerance must be in (0, target)");
  if (o.seeds.per_pore < 0 || o.seeds.per_pore > 2) throw CellGenerationError(R::BadOption, "seeds per pore must be 0, 1 or 2");
  // A seed reaches at most its length from its pore, so seeds shorter than half the ligament can
  // neither meet another pore, another seed nor an edge.
  if (o.seeds.per_pore > 0 && !(o.seeds.length_m > 0.0 && 2.0 * o.seeds.length_m < lig))
    throw CellGenerationError(R::BadOption, "seed length must be > 0 and below half the minimum ligament");
  if (!(std::fabs(o.seeds.tilt_rad) < 0.5 * M_PI))
    throw CellGenerationError(R::BadOption, "seed tilt must be below 90 degrees in magnitude");
}

GeneratedCell generate_cell(const CellOptions& options, std::uint64_t seed) {
  check_cell_options(options);
  const BurrXII burr(options.burr, options.truncation_m);
  std::mt19937_64 rng(seed);
  GeneratedCell cell;
  cell.seed = seed;
  cell.geometry.side_m = options.side_m;
  cell.geometry.load = options.load;
  std::vector<double> diameters = draw_diameters(options, burr, rng, cell.record);
  cell.geometry.pores = place_pores(std::move(diameters), options, rng, cell.record);
  cell.geometry.seeds = make_seeds(cell.geometry.pores, options, rng);
  return cell;
}

std::uint64_t derive_cell_seed(std::uint64_t base_seed, std::uint64_t size_index, std::uint64_t realization) {
  std::uint64_t h = splitmix64(base_seed);
  h = splitmix64(h ^ (size_index + 1));
  h = splitmix64(h ^ (realization + 1) * 0x632BE59BD9B4E019ULL);
  return h >> 11;  // 53 bits
}

}  // namespace uhpc::micro
