#include <algorithm>
#include <cmath>

#include "cell_mesh.hpp"

namespace uhpc::micro {

namespace {

double distance_to_segment(double x, double y, const Vec2& a, const Vec2& b) {
  const double ex = b.x - a.x, ey = b.y - a.y, l2 = ex * ex + ey * ey;
  double t = l2 > 0.0 ? ((x - a.x) * ex + (y - a.y) * ey) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(x - a.x - t * ex, y - a.y - t * ey);
}

}  // namespace

CellSizeField::CellSizeField(const CellGeometry& cell, const MeshOptions& options) : cell_(&cell), options_(options) {
  const double fine = options.boundary_ratio * options.nominal_spacing_m;
  double smallest = fine;
  for (const Pore& p : cell.pores) {
    pore_size_.push_back(std::min(fine, M_PI * p.diameter_m / options.min_nodes_per_pore));
    smallest = std::min(smallest, pore_size_.back());
  }
  reach_ = std::max((options.nominal_spacing_m - smallest) / options.grading, 1e-12);
  buckets_ = std::clamp(static_cast<int>(cell.side_m / reach_), 1, 1024);
  bucket_.assign(static_cast<std::size_t>(buckets_) * buckets_, {});
  const double edge = cell.side_m / buckets_;
  auto bucket_index = [&](double v) { return std::clamp(static_cast<int>(std::floor(v / edge)), 0, buckets_ - 1); };
  // Registers feature `id` in every bucket its bounding box, grown by reach_, overlaps.
  auto add = [&](int id, double x0, double y0, double x1, double y1) {
    for (int j = bucket_index(y0 - reach_); j <= bucket_index(y1 + reach_); ++j)
      for (int i = bucket_index(x0 - reach_); i <= bucket_index(x1 + reach_); ++i)
        bucket_[static_cast<std::size_t>(j) * buckets_ + i].push_back(id);
  };
  const int pores = static_cast<int>(cell.pores.size());
  for (int p = 0; p < pores; ++p) {
    const Pore& q = cell.pores[p];
    const double r = q.radius_m();
    add(p, q.center_m.x - r, q.center_m.y - r, q.center_m.x + r, q.center_m.y + r);
  }
  for (std::size_t k = 0; k < cell.seeds.size(); ++k) {
    const CrackSeed& c = cell.seeds[k];
    add(pores + static_cast<int>(k), std::min(c.root_m.x, c.tip_m.x), std::min(c.root_m.y, c.tip_m.y),
        std::max(c.root_m.x, c.tip_m.x), std::max(c.root_m.y, c.tip_m.y));
  }
}

std::size_t CellSizeField::bucket_of(double x, double y) const {
  const double edge = cell_->side_m / buckets_;
  const int i = std::clamp(static_cast<int>(std::floor(x / edge)), 0, buckets_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor(y / edge)), 0, buckets_ - 1);
  return static_cast<std::size_t>(j) * buckets_ + i;
}

int CellSizeField::pore_boundary_segments(std::size_t p) const {
  const double circumference = M_PI * cell_->pores[p].diameter_m;
  const int n = std::max(options_.min_nodes_per_pore, static_cast<int>(std::ceil(circumference / pore_size_[p] - 1e-9)));
  return 4 * ((n + 3) / 4);
}

double CellSizeField::operator()(double x, double y) const {
  const double g = options_.grading;
  const double fine = options_.boundary_ratio * options_.nominal_spacing_m;
  const int pores = static_cast<int>(cell_->pores.size());
  double size = options_.nominal_spacing_m;
  // A point outside the cell (gmsh may probe slightly outside) falls into the nearest bucket; features
  // outside its reach cannot lower the size below nominal, so the answer is the same as a full scan.
  for (int id : bucket_[bucket_of(x, y)]) {
    if (id < pores) {
      const Pore& p = cell_->pores[id];
      const double d = std::max(0.0, std::hypot(x - p.center_m.x, y - p.center_m.y) - p.radius_m());
      size = std::min(size, pore_size_[id] + g * d);
    } else {
      const CrackSeed& s = cell_->seeds[id - pores];
      size = std::min(size, fine + g * distance_to_segment(x, y, s.root_m, s.tip_m));
    }
  }
  return size;
}

}  // namespace uhpc::micro
