#pragma once
// A known answer for energy bridging: a 1D bar of length L (a square L x L cell per unit thickness,
// no pores) with one linear-softening cohesive crack across it, under imposed end displacement.
//   before cracking: sigma = E e                        (e <= e_t = f_t / E)
//   after:           sigma = f_t (1 - w / w_c),  e = sigma / E + w / L,  w_c = 2 G_f / f_t
// The path is parameterized by the opening w; de/dw = 1/L - f_t/(E w_c) < 0 (snap-back) when
// L > E w_c / f_t = 2 l_ch. Energies per unit thickness: bulk sigma^2/(2E) L^2, recoverable cohesive
// 1/2 sigma w L, dissipated (secant unloading) 1/2 f_t w L (G_f L at separation), so Psi_bar =
// 1/2 sigma e exactly and d_energy = d_force.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cell_response.hpp"

namespace uhpc::test {

struct CohesiveBar {
  double E = 4.4296e10;   // Table 2 matrix
  double f_t = 2.27e7;
  double G_f = 35.0;
  double L = 0.003;

  double w_c() const { return 2.0 * G_f / f_t; }
  double e_t() const { return f_t / E; }
  double e_separation() const { return w_c() / L; }
  double slope() const { return 1.0 / L - e_t() / w_c(); }  // de/dw on the softening branch
  bool snaps_back() const { return slope() < 0.0; }

  micro::CellState elastic(double e) const {
    micro::CellState s;
    s.strain = e;
    s.sigma_bar_Pa = E * e;
    s.bulk_energy_J_m = 0.5 * E * e * e * L * L;
    s.external_work_J_m = s.bulk_energy_J_m;
    s.crack_segments = 1;
    return s;
  }
  micro::CellState cracked(double w) const {
    micro::CellState s;
    s.sigma_bar_Pa = f_t * (1.0 - w / w_c());
    s.strain = s.sigma_bar_Pa / E + w / L;
    s.bulk_energy_J_m = s.sigma_bar_Pa * s.sigma_bar_Pa / (2.0 * E) * L * L;
    s.cohesive_energy_J_m = 0.5 * s.sigma_bar_Pa * w * L;
    s.dissipated_J_m = 0.5 * f_t * w * L;
    s.external_work_J_m = s.bulk_energy_J_m + s.cohesive_energy_J_m + s.dissipated_J_m;
    s.max_opening_m = w;
    s.crack_segments = 1;
    s.open_segments = w > 0.0 ? 1 : 0;
    s.newton_iterations = 3;
    return s;
  }
  // `elastic_states` states up to the peak (the last one at e_t, still closed), then `cracked_states`
  // states with w evenly spaced in (0, w_c]: the last one is the separated bar (sigma = 0).
  micro::CellResponse response(int elastic_states = 10, int cracked_states = 200) const {
    micro::CellResponse r;
    r.side_m = L;
    r.E0_bar_Pa = E;
    r.porosity = 0.0;
    for (int k = 0; k <= elastic_states; ++k) r.states.push_back(elastic(e_t() * k / elastic_states));
    for (int k = 1; k <= cracked_states; ++k) r.states.push_back(cracked(w_c() * k / cracked_states));
    r.status = micro::CellStatus::Separated;
    r.nodes = 2;
    r.dofs = 3;
    return r;
  }

  // Closed form of the strain-controlled test (what a test machine holding e would see).
  double damage(double e) const {
    if (e <= e_t()) return 0.0;
    if (snaps_back() || e >= e_separation()) return 1.0;  // a snap-back jumps straight to separation
    const double w = (e - e_t()) / slope();
    return 1.0 - f_t * (1.0 - w / w_c()) / (E * e);
  }
  double stress(double e) const { return (1.0 - damage(e)) * E * e; }
  // Strain at d = 0.5 of the strain-controlled curve.
  double strain_at_half_damage() const {
    if (snaps_back()) return e_t();
    // 1 - sigma/(E e) = 1/2 with sigma = f_t (1 - w/w_c), e = e_t + w slope: linear in w.
    // f_t (1 - w/w_c) = E (e_t + w slope) / 2  ->  w (f_t/w_c + E slope / 2) = f_t - E e_t / 2
    const double w = (f_t - 0.5 * E * e_t()) / (f_t / w_c() + 0.5 * E * slope());
    return e_t() + w * slope();
  }
};

}  // namespace uhpc::test
