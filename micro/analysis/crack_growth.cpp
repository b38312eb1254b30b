#include "crack_growth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace uhpc::micro {

namespace {

bool in_matrix(const CellGeometry& cell, double x, double y) {
  if (x < 0.0 || y < 0.0 || x > cell.side_m || y > cell.side_m) return false;
  for (const Pore& p : cell.pores)
    if (std::hypot(x - p.center_m.x, y - p.center_m.y) < p.radius_m()) return false;
  return true;
}

// Direction the tip currently points in (the last active segment, or the planned first one).
Vec2 tip_direction(const Crack& c) {
  const std::size_t s = c.active > 0 ? c.active - 1 : 0;
  return c.segment_direction(s);
}

// First parameter t in (0, 1] where segment p -> q enters circle (center, r); -1 if none.
double circle_entry(const Vec2& p, const Vec2& q, const Vec2& center, double r) {
  const double dx = q.x - p.x, dy = q.y - p.y, fx = p.x - center.x, fy = p.y - center.y;
  const double a = dx * dx + dy * dy, b = 2.0 * (fx * dx + fy * dy), c = fx * fx + fy * fy - r * r;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return -1.0;
  const double t = (-b - std::sqrt(disc)) / (2.0 * a);
  return t > 1e-9 && t <= 1.0 ? t : -1.0;
}

}  // namespace

double local_spacing(const CellDiscretization& mesh, const Vec2& x) {
  double best = std::numeric_limits<double>::infinity(), h = mesh.spacing_m.empty() ? 0.0 : mesh.spacing_m[0];
  for (std::size_t i = 0; i < mesh.node_count(); ++i) {
    const double d = std::hypot(mesh.nodes_m[i][0] - x.x, mesh.nodes_m[i][1] - x.y);
    if (d < best) {
      best = d;
      h = mesh.spacing_m[i];
    }
  }
  return h;
}

std::vector<Crack> cracks_from_seeds(const CellGeometry& cell, const CellDiscretization& mesh,
                                     const GrowthOptions& options) {
  std::vector<Crack> out;
  const double edge_tol = 1e-9 * cell.side_m;
  for (std::size_t s = 0; s < cell.seeds.size(); ++s) {
    const CrackSeed& seed = cell.seeds[s];
    Crack c;
    c.seed = static_cast<int>(s);
    c.root = seed.pore >= 0 ? CrackEnd::Pore : CrackEnd::Edge;
    const double len = std::hypot(seed.tip_m.x - seed.root_m.x, seed.tip_m.y - seed.root_m.y);
    const double inc = options.increment_spacings * local_spacing(mesh, seed.root_m);
    const int pieces = std::max(1, static_cast<int>(std::lround(len / inc)));
    for (int k = 0; k <= pieces; ++k) {
      const double t = static_cast<double>(k) / pieces;
      c.points.push_back({seed.root_m.x + t * (seed.tip_m.x - seed.root_m.x), seed.root_m.y + t * (seed.tip_m.y - seed.root_m.y)});
    }
    const Vec2& tip = seed.tip_m;
    if (tip.x <= edge_tol || tip.y <= edge_tol || tip.x >= cell.side_m - edge_tol || tip.y >= cell.side_m - edge_tol)
      c.tip_end = CrackEnd::Edge;
    out.push_back(std::move(c));
  }
  return out;
}

TipSamples tip_samples(const CellGeometry& cell, const CellDiscretization& mesh, const std::vector<Crack>& cracks,
                       const GrowthOptions& options) {
  TipSamples s;
  constexpr int kRings = 4, kRays = 9;
  for (std::size_t c = 0; c < cracks.size(); ++c) {
    const Crack& k = cracks[c];
    if (k.stopped()) continue;
    const Vec2 tip = k.tip();
    const Vec2 dir = k.has_planned() ? k.segment_direction(k.active) : tip_direction(k);
    const double r = options.average_radius_spacings * local_spacing(mesh, tip);
    for (int i = 1; i <= kRings; ++i)
      for (int j = 0; j < kRays; ++j) {
        const double rho = r * (i - 0.5) / kRings;
        const double phi = -0.5 * M_PI + M_PI * (j + 0.5) / kRays;
        const double x = tip.x + rho * (std::cos(phi) * dir.x - std::sin(phi) * dir.y);
        const double y = tip.y + rho * (std::sin(phi) * dir.x + std::cos(phi) * dir.y);
        if (!in_matrix(cell, x, y)) continue;
        s.x.push_back(x);
        s.x.push_back(y);
        s.crack.push_back(static_cast<int>(c));
      }
  }
  return s;
}

std::vector<TipCriterion> tip_criteria(const std::vector<Crack>& cracks, const TipSamples& samples,
                                       const std::vector<std::array<double, 3>>& stress) {
  std::vector<TipCriterion> out(cracks.size());
  std::vector<std::array<double, 3>> mean(cracks.size(), {0.0, 0.0, 0.0});
  std::vector<int> count(cracks.size(), 0);
  // Rings weighted by their area (the samples are on equal-angle rays at ring mid radii).
  for (std::size_t p = 0; p < samples.crack.size(); ++p) {
    const int c = samples.crack[p];
    for (int k = 0; k < 3; ++k) mean[c][k] += stress[p][k];
    ++count[c];
  }
  for (std::size_t c = 0; c < cracks.size(); ++c) {
    if (count[c] == 0) continue;
    const Crack& k = cracks[c];
    const double sx = mean[c][0] / count[c], sy = mean[c][1] / count[c], sxy = mean[c][2] / count[c];
    TipCriterion& t = out[c];
    t.valid = true;
    if (k.has_planned()) {
      const Vec2 d = k.segment_direction(k.active);
      const double n[2] = {-d.y, d.x};
      t.stress_Pa = sx * n[0] * n[0] + sy * n[1] * n[1] + 2.0 * sxy * n[0] * n[1];
      t.direction = d;
    } else {
      const double c0 = 0.5 * (sx + sy), rr = std::hypot(0.5 * (sx - sy), sxy);
      t.stress_Pa = c0 + rr;
      const double theta = 0.5 * std::atan2(2.0 * sxy, sx - sy);  // principal direction of sigma_1
      Vec2 d{-std::sin(theta), std::cos(theta)};                   // normal to it
      const Vec2 cur = tip_direction(k);
      if (d.x * cur.x + d.y * cur.y < 0.0) d = {-d.x, -d.y};
      t.direction = d;
    }
  }
  return out;
}

bool advance_crack(std::vector<Crack>& cracks, std::size_t c, const Vec2& direction, const CellGeometry& cell,
                   const CellDiscretization& mesh, const GrowthOptions& options) {
  Crack& k = cracks[c];
  if (k.has_planned()) {
    ++k.active;
    return true;
  }
  if (k.tip_end != CrackEnd::Open) return false;
  const Vec2 p = k.tip();
  const double inc = options.increment_spacings * local_spacing(mesh, p);
  // Look 1.5 increments ahead, so that a tip never stops a sliver short of a pore, an edge or a crack.
  const Vec2 far{p.x + 1.5 * inc * direction.x, p.y + 1.5 * inc * direction.y};
  double t_hit = 2.0;
  CrackEnd what = CrackEnd::Open;
  int junction = -1;
  Vec2 far_join;
  // Cell edges.
  const double dx = far.x - p.x, dy = far.y - p.y;
  auto edge = [&](double num, double den) {
    if (den == 0.0) return;
    const double t = num / den;
    if (t > 1e-12 && t <= 1.0 && t < t_hit) {
      t_hit = t;
      what = CrackEnd::Edge;
    }
  };
  edge(-p.x, dx);
  edge(cell.side_m - p.x, dx);
  edge(-p.y, dy);
  edge(cell.side_m - p.y, dy);
  for (const Pore& pore : cell.pores) {
    const double t = circle_entry(p, far, pore.center_m, pore.radius_m());
    if (t > 0.0 && t < t_hit) {
      t_hit = t;
      what = CrackEnd::Pore;
    }
  }
  for (std::size_t o = 0; o < cracks.size(); ++o) {
    if (o == c) continue;
    for (std::size_t s = 0; s < cracks[o].active; ++s) {
      const double t = segment_intersection(p, far, cracks[o].points[s], cracks[o].points[s + 1]);
      if (t > 1e-9 && t < t_hit) {
        t_hit = t;
        what = CrackEnd::Crack;
        junction = static_cast<int>(o);
      }
    }
  }
  // Coalescence: a tip that would pass within coalescence_spacings x increment of another crack
  // (or a pore) without crossing it joins it at the nearest point, so that parallel cracks do not
  // overlap with a thin sliver between them that nothing would ever cut.
  if (what == CrackEnd::Open && options.coalescence_spacings > 0.0) {
    const double reach = options.coalescence_spacings * inc;
    const Vec2 ahead{p.x + inc * direction.x, p.y + inc * direction.y};
    double best = reach;
    for (std::size_t o = 0; o < cracks.size(); ++o) {
      if (o == c || cracks[o].active == 0) continue;
      for (std::size_t s = 0; s < cracks[o].active; ++s) {
        const Vec2& a = cracks[o].points[s];
        const Vec2& b = cracks[o].points[s + 1];
        const double ex = b.x - a.x, ey = b.y - a.y;
        for (const Vec2& from : {p, ahead}) {
          const double t = std::clamp(((from.x - a.x) * ex + (from.y - a.y) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
          const Vec2 cpt{a.x + t * ex, a.y + t * ey};
          const double dist = std::hypot(cpt.x - from.x, cpt.y - from.y);
          const double fwd = (cpt.x - p.x) * direction.x + (cpt.y - p.y) * direction.y;
          const double len = std::hypot(cpt.x - p.x, cpt.y - p.y);
          // Ahead of the tip or beside it, never behind; and not a degenerate join.
          if (dist < best && fwd > -0.1 * len && len > 0.2 * inc) {
            best = dist;
            what = CrackEnd::Crack;
            junction = static_cast<int>(o);
            t_hit = -1.0;
            far_join = cpt;
          }
        }
      }
    }
  }
  Vec2 q;
  if (what == CrackEnd::Crack && t_hit < 0.0) {
    q = far_join;
  } else if (what == CrackEnd::Open) {
    q = {p.x + inc * direction.x, p.y + inc * direction.y};
  } else {
    q = {p.x + t_hit * dx, p.y + t_hit * dy};
    if (std::hypot(q.x - p.x, q.y - p.y) < 1e-3 * inc) {
      k.tip_end = what;  // already touching: stop without a degenerate segment
      return false;
    }
  }
  if (what == CrackEnd::Crack) {
    k.junction = junction;
    const double mid[2] = {0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
    k.junction_side = crack_side(cracks[junction], mid);
  }
  k.points.push_back(q);
  k.active = k.points.size() - 1;
  k.tip_end = what;
  return true;
}

}  // namespace uhpc::micro
