#include "materials/afc_hydrostat.hpp"

#include <algorithm>
#include <cmath>

namespace uhpc::macro {

AfcHydrostat::AfcHydrostat(const AfcParams& p)
    : C6_(p.C6_Pa), C7_(p.C7), C8_(p.C8_Pa), C9_(p.C9), K1_(p.K1_Pa), K2_(p.K2_Pa), K3_(p.K3_Pa),
      K_e_(p.C6_Pa / p.C7), P9_(0.0) {
  const double x = C9_ - C7_;
  P9_ = C6_ + x * (K1_ + x * (K2_ + x * K3_));
}

double AfcHydrostat::loading_pressure(double mu) const {
  if (mu <= C7_) return K_e_ * mu;
  if (mu <= C9_) {
    const double x = mu - C7_;
    return C6_ + x * (K1_ + x * (K2_ + x * K3_));
  }
  return P9_ + C8_ * (mu - C9_);
}

double AfcHydrostat::loading_slope(double mu) const {
  if (mu < C7_) return K_e_;
  if (mu < C9_) {
    const double x = mu - C7_;
    return K1_ + x * (2.0 * K2_ + x * 3.0 * K3_);
  }
  return C8_;
}

double AfcHydrostat::unloading_modulus(double mu_max) const {
  const double F = std::clamp((mu_max - C7_) / (C9_ - C7_), 0.0, 1.0);
  return K_e_ + F * (C8_ - K_e_);
}

double AfcHydrostat::crushing_strain(double mu_max) const {
  if (mu_max <= C7_) return 0.0;
  return mu_max - loading_pressure(mu_max) / unloading_modulus(mu_max);
}

double AfcHydrostat::uncut_pressure(double mu, double mu_max) const {
  return mu >= mu_max ? loading_pressure(mu) : loading_pressure(mu_max) + unloading_modulus(mu_max) * (mu - mu_max);
}

double AfcHydrostat::pressure(double mu, double mu_max, double cutoff_Pa) const {
  return std::max(uncut_pressure(mu, mu_max), -cutoff_Pa);
}

double AfcHydrostat::slope(double mu, double mu_max) const {
  return mu >= mu_max ? loading_slope(mu) : unloading_modulus(mu_max);
}

double AfcHydrostat::recoverable_work(double m, double o) const {
  // Line P = K_u (1 + mu) + c with c = P_L(m) - K_u (1 + m); with u = 1 + mu + o, P = K_u u + c - K_u o
  // and the antiderivative of P / u^2 is K_u ln(u) - (c - K_u o) / u.
  const double K = unloading_modulus(m), c = loading_pressure(m) - K * (1.0 + m);
  const auto W = [&](double mu) { return K * std::log1p(mu + o) - (c - K * o) / (1.0 + mu + o); };
  return W(m) - W(crushing_strain(m));
}

double AfcHydrostat::loading_work(double a, double b, double o) const {
  // Composite Simpson on each smooth piece (the curve has kinks at C7 and C9).
  const auto f = [&](double mu) { return loading_pressure(mu) / ((1.0 + mu + o) * (1.0 + mu + o)); };
  const auto simpson = [&](double lo, double hi) {
    if (!(hi > lo)) return 0.0;
    constexpr int n = 16;  // even
    const double h = (hi - lo) / n;
    double sum = f(lo) + f(hi);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
    return sum * h / 3.0;
  };
  const double k1 = std::clamp(C7_, a, b), k2 = std::clamp(C9_, a, b);
  return simpson(a, k1) + simpson(k1, k2) + simpson(k2, b);
}

double AfcHydrostat::crushing_dissipation(double m0, double m1, double o) const {
  if (!(m1 > m0) || m1 <= C7_) return 0.0;
  const double a = std::max(m0, C7_);
  // Below C7 loading and recoverable work coincide (elastic); only the part above C7 dissipates.
  return loading_work(a, m1, o) - (recoverable_work(m1, o) - recoverable_work(a, o));
}

}  // namespace uhpc::macro
