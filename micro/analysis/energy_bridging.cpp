#include "energy_bridging.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

namespace uhpc::micro {

const char* to_string(StrainControl c) {
  return c == StrainControl::FirstPassage ? "first_passage" : "max_below";
}

const char* to_string(DamageMeasure m) { return m == DamageMeasure::Energy ? "energy" : "force"; }

std::optional<StrainControl> strain_control_from_name(std::string_view name) {
  if (name == "first_passage") return StrainControl::FirstPassage;
  if (name == "max_below") return StrainControl::MaxBelow;
  return std::nullopt;
}

std::optional<DamageMeasure> damage_measure_from_name(std::string_view name) {
  if (name == "energy") return DamageMeasure::Energy;
  if (name == "force") return DamageMeasure::Force;
  return std::nullopt;
}

BridgedPath bridge_energy(const CellResponse& r) {
  if (r.states.empty()) throw std::invalid_argument("energy bridging: the response has no states");
  if (!(r.side_m > 0.0) || !std::isfinite(r.side_m))
    throw std::invalid_argument(fmt::format("energy bridging: cell side {} m is not positive", r.side_m));
  if (!(r.E0_bar_Pa > 0.0) || !std::isfinite(r.E0_bar_Pa))
    throw std::invalid_argument(fmt::format("energy bridging: E0_bar {} Pa is not positive", r.E0_bar_Pa));
  BridgedPath p;
  p.cell_area_m2 = r.side_m * r.side_m;  // the whole cell, pores included (the continuum's volume)
  const std::size_t n = r.states.size();
  p.psi_bar_J_m3.resize(n);
  p.psi_0_J_m3.resize(n);
  p.d_energy.resize(n);
  p.d_force.resize(n);
  p.cracked.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const CellState& s = r.states[i];
    for (double v : {s.strain, s.sigma_bar_Pa, s.bulk_energy_J_m, s.cohesive_energy_J_m}) {
      if (!std::isfinite(v))
        throw std::invalid_argument(fmt::format("energy bridging: state {} has a non-finite value", i));
    }
    p.psi_bar_J_m3[i] = (s.bulk_energy_J_m + s.cohesive_energy_J_m) / p.cell_area_m2;
    p.psi_0_J_m3[i] = 0.5 * r.E0_bar_Pa * s.strain * s.strain;
    p.cracked[i] = s.open_segments > 0 && s.strain != 0.0;
    if (!p.cracked[i]) {
      // Undamaged by definition: the ratios would only show the discretization's Hill-Mandel error.
      p.d_energy[i] = 0.0;
      p.d_force[i] = 0.0;
      continue;
    }
    p.d_energy[i] = 1.0 - p.psi_bar_J_m3[i] / p.psi_0_J_m3[i];
    p.d_force[i] = 1.0 - s.sigma_bar_Pa / (r.E0_bar_Pa * s.strain);
    const double diff = std::abs(p.d_energy[i] - p.d_force[i]);
    if (diff > p.max_abs_difference) {
      p.max_abs_difference = diff;
      p.max_difference_state = i;
    }
  }
  return p;
}

double bridged_damage(const BridgedPath& path, std::size_t i, DamageMeasure measure) {
  const double d = measure == DamageMeasure::Energy ? path.d_energy[i] : path.d_force[i];
  return std::clamp(d, 0.0, 1.0);
}

namespace {

double lerp(double a, double b, double t) { return a + t * (b - a); }

// Where the damage is the running maximum the path's own stress is kept; where it is held above the
// path's (a jump, or damage that fell back through round-off) the stress is the damaged secant one.
double stress_at(double d_path, double d_held, double sigma_path, double E0, double e) {
  return d_path >= d_held ? sigma_path : (1.0 - d_held) * E0 * e;
}

ControlledCurve first_passage(const CellResponse& r, const BridgedPath& p, DamageMeasure m) {
  ControlledCurve c;
  const double E0 = r.E0_bar_Pa;
  auto push = [&c](double e, double d, double s) {
    c.strain.push_back(e);
    c.damage.push_back(d);
    c.stress_Pa.push_back(s);
  };
  const auto& st = r.states;
  double e_max = st[0].strain;
  double d_max = bridged_damage(p, 0, m);
  push(e_max, d_max, st[0].sigma_bar_Pa);
  for (std::size_t i = 1; i < st.size(); ++i) {
    const double ea = st[i - 1].strain, eb = st[i].strain;
    const double da = bridged_damage(p, i - 1, m), db = bridged_damage(p, i, m);
    const double sa = st[i - 1].sigma_bar_Pa, sb = st[i].sigma_bar_Pa;
    if (eb > e_max || (eb == e_max && ea < e_max)) {
      if (ea < e_max) {
        // The path comes back above the largest strain seen so far: a strain-controlled test has
        // been holding at e_max and jumps here.
        const double t = (e_max - ea) / (eb - ea);
        const double d_entry = lerp(da, db, t);
        const double d_held = std::max(d_max, d_entry);
        push(e_max, d_held, stress_at(d_entry, d_held, lerp(sa, sb, t), E0, e_max));
        if (d_held > c.damage[c.damage.size() - 2]) ++c.jumps;
        d_max = d_held;
      }
      d_max = std::max(d_max, db);
      if (eb > e_max) push(eb, d_max, stress_at(db, d_max, sb, E0, eb));
      e_max = eb;
    } else {
      d_max = std::max(d_max, db);  // damage grown on a snap-back counts once the test gets there
    }
  }
  return c;
}

ControlledCurve max_below(const CellResponse& r, const BridgedPath& p, DamageMeasure m) {
  ControlledCurve c;
  const auto& st = r.states;
  std::vector<std::size_t> order(st.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&st](std::size_t a, std::size_t b) { return st[a].strain < st[b].strain; });
  double d_max = 0.0;
  for (std::size_t i : order) {
    const double d = bridged_damage(p, i, m);
    d_max = std::max(d_max, d);
    c.strain.push_back(st[i].strain);
    c.damage.push_back(d_max);
    c.stress_Pa.push_back(stress_at(d, d_max, st[i].sigma_bar_Pa, r.E0_bar_Pa, st[i].strain));
  }
  for (std::size_t k = 1; k < c.damage.size(); ++k) {
    if (c.damage[k] > c.damage[k - 1] + 0.25) ++c.jumps;  // only as a hint; the curve has no true jumps
  }
  return c;
}

}  // namespace

ControlledCurve strain_controlled_curve(const CellResponse& r, const BridgedPath& p, const BridgingOptions& o) {
  if (p.d_energy.size() != r.states.size() || r.states.empty())
    throw std::invalid_argument("strain_controlled_curve: the bridged path does not match the response");
  ControlledCurve c = o.strain_control == StrainControl::FirstPassage ? first_passage(r, p, o.damage_measure)
                                                                      : max_below(r, p, o.damage_measure);
  c.separated = r.status == CellStatus::Separated;
  double e_max = r.states[0].strain;
  for (const CellState& s : r.states) {
    if (s.strain < e_max - 1e-12 * std::abs(e_max)) c.snap_back = true;
    e_max = std::max(e_max, s.strain);
  }
  return c;
}

ResampledCurve resample(const ControlledCurve& c, const std::vector<double>& grid, double E0) {
  if (c.strain.empty()) throw std::invalid_argument("resample: empty curve");
  ResampledCurve out;
  out.damage.resize(grid.size());
  out.stress_Pa.resize(grid.size());
  const double end = c.strain.back();
  for (std::size_t j = 0; j < grid.size(); ++j) {
    const double g = grid[j];
    double d = 0.0, s = 0.0;
    if (g > end) {
      if (c.separated) {
        d = 1.0;
        s = 0.0;
      } else {
        d = c.damage.back();
        s = (1.0 - d) * E0 * g;
      }
    } else {
      ++out.valid_points;
      // First vertex at or above g: at a vertical jump on g this is the state before the jump.
      const auto k = static_cast<std::size_t>(std::lower_bound(c.strain.begin(), c.strain.end(), g) - c.strain.begin());
      if (k == 0) {
        d = c.damage[0];
        s = (1.0 - d) * E0 * g;
      } else {
        const double t = (g - c.strain[k - 1]) / (c.strain[k] - c.strain[k - 1]);
        d = lerp(c.damage[k - 1], c.damage[k], t);
        s = lerp(c.stress_Pa[k - 1], c.stress_Pa[k], t);
      }
    }
    out.damage[j] = d;
    out.stress_Pa[j] = s;
  }
  out.complete = out.valid_points == grid.size() || c.separated;
  return out;
}

CurveFeatures curve_features(const CellResponse& r, const BridgedPath& p, const ControlledCurve& c) {
  CurveFeatures f;
  for (const CellState& s : r.states) {
    if (s.sigma_bar_Pa > f.peak_stress_Pa) {
      f.peak_stress_Pa = s.sigma_bar_Pa;
      f.strain_at_peak = s.strain;
    }
    f.max_strain = std::max(f.max_strain, s.strain);
  }
  for (std::size_t k = 0; k < c.damage.size(); ++k) {
    if (c.damage[k] < 0.5) continue;
    if (k == 0 || c.strain[k] == c.strain[k - 1]) {
      f.strain_at_half_damage = c.strain[k];
    } else {
      const double t = (0.5 - c.damage[k - 1]) / (c.damage[k] - c.damage[k - 1]);
      f.strain_at_half_damage = lerp(c.strain[k - 1], c.strain[k], t);
    }
    break;
  }
  // A separated curve that never reached 0.5 jumps to d = 1 at its end.
  if (!f.strain_at_half_damage && c.separated) f.strain_at_half_damage = c.strain.back();
  f.dissipated_J_m = r.states.back().dissipated_J_m;
  f.dissipated_per_area_J_m3 = f.dissipated_J_m / p.cell_area_m2;
  return f;
}

}  // namespace uhpc::micro
