#include "quadrature.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace uhpc::micro {

namespace {

// Adds the 3 points (b, a, a), (a, b, a), (a, a, b).
void add_orbit3(std::vector<TrianglePoint>& r, double a, double w) {
  const double b = 1.0 - 2.0 * a;
  r.push_back({{b, a, a}, w});
  r.push_back({{a, b, a}, w});
  r.push_back({{a, a, b}, w});
}

// Adds the 6 permutations of (a, b, c), c = 1 - a - b.
void add_orbit6(std::vector<TrianglePoint>& r, double a, double b, double w) {
  const double c = 1.0 - a - b;
  for (const std::array<double, 3>& p : {std::array<double, 3>{a, b, c}, {a, c, b}, {b, a, c}, {b, c, a}, {c, a, b},
                                         {c, b, a}})
    r.push_back({p, w});
}

std::vector<TrianglePoint> make_triangle_rule(int points) {
  std::vector<TrianglePoint> r;
  switch (points) {
    case 1:
      r.push_back({{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, 1.0});
      break;
    case 3:
      add_orbit3(r, 1.0 / 6.0, 1.0 / 3.0);
      break;
    case 6:  // Dunavant degree 4
      add_orbit3(r, 0.445948490915965, 0.223381589678011);
      add_orbit3(r, 0.091576213509771, 0.109951743655322);
      break;
    case 7:  // Dunavant degree 5
      r.push_back({{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, 0.225});
      add_orbit3(r, 0.470142064105115, 0.132394152788506);
      add_orbit3(r, 0.101286507323456, 0.125939180544827);
      break;
    case 12:  // Dunavant degree 6
      add_orbit3(r, 0.249286745170910, 0.116786275726379);
      add_orbit3(r, 0.063089014491502, 0.050844906370207);
      add_orbit6(r, 0.053145049844817, 0.310352451033784, 0.082851075618374);
      break;
    default:
      throw std::invalid_argument("no triangle rule with " + std::to_string(points) +
                                  " points; available: 1, 3, 6, 7, 12");
  }
  // The tabulated weights carry 15 digits: renormalize so that constants integrate to round-off.
  double sum = 0.0;
  for (const TrianglePoint& p : r) sum += p.weight;
  for (TrianglePoint& p : r) p.weight /= sum;
  return r;
}

std::vector<LinePoint> make_line_rule(int points) {
  std::vector<std::pair<double, double>> ref;  // (xi in [-1, 1], weight summing to 2)
  switch (points) {
    case 1: ref = {{0.0, 2.0}}; break;
    case 2: ref = {{-1.0 / std::sqrt(3.0), 1.0}, {1.0 / std::sqrt(3.0), 1.0}}; break;
    case 3: ref = {{-std::sqrt(0.6), 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {std::sqrt(0.6), 5.0 / 9.0}}; break;
    case 4:
      ref = {{-0.8611363115940526, 0.3478548451374538}, {-0.3399810435848563, 0.6521451548625461},
             {0.3399810435848563, 0.6521451548625461}, {0.8611363115940526, 0.3478548451374538}};
      break;
    case 5:
      ref = {{-0.9061798459386640, 0.2369268850561891}, {-0.5384693101056831, 0.4786286704993665},
             {0.0, 0.5688888888888889}, {0.5384693101056831, 0.4786286704993665},
             {0.9061798459386640, 0.2369268850561891}};
      break;
    default:
      throw std::invalid_argument("no Gauss-Legendre rule with " + std::to_string(points) + " points; available: 1..5");
  }
  std::vector<LinePoint> r;
  for (const auto& [xi, w] : ref) r.push_back({0.5 * (1.0 + xi), 0.5 * w});
  return r;
}

}  // namespace

bool is_triangle_rule(int points) { return points == 1 || points == 3 || points == 6 || points == 7 || points == 12; }

int triangle_rule_degree(int points) {
  switch (points) {
    case 1: return 1;
    case 3: return 2;
    case 6: return 4;
    case 7: return 5;
    case 12: return 6;
    default: break;
  }
  throw std::invalid_argument("no triangle rule with " + std::to_string(points) + " points; available: 1, 3, 6, 7, 12");
}

const std::vector<TrianglePoint>& triangle_rule(int points) {
  // Built once per count (function-local statics are initialized thread-safely).
  static const std::vector<TrianglePoint> r1 = make_triangle_rule(1), r3 = make_triangle_rule(3),
                                          r6 = make_triangle_rule(6), r7 = make_triangle_rule(7),
                                          r12 = make_triangle_rule(12);
  switch (points) {
    case 1: return r1;
    case 3: return r3;
    case 6: return r6;
    case 7: return r7;
    case 12: return r12;
    default: break;
  }
  throw std::invalid_argument("no triangle rule with " + std::to_string(points) + " points; available: 1, 3, 6, 7, 12");
}

const std::vector<LinePoint>& line_rule(int points) {
  static const std::vector<LinePoint> rules[5] = {make_line_rule(1), make_line_rule(2), make_line_rule(3),
                                                  make_line_rule(4), make_line_rule(5)};
  if (points < 1 || points > 5)
    throw std::invalid_argument("no Gauss-Legendre rule with " + std::to_string(points) + " points; available: 1..5");
  return rules[points - 1];
}

}  // namespace uhpc::micro
