#include "crack_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace uhpc::micro {

namespace {

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

struct Closest {
  double distance = std::numeric_limits<double>::infinity();
  std::size_t segment = 0;
  double t = 0.0;  // parameter on the segment, clamped to [0, 1]
};

Closest closest(const Crack& c, const double* x) {
  Closest best;
  for (std::size_t s = 0; s < c.active; ++s) {
    const Vec2& a = c.points[s];
    const Vec2& b = c.points[s + 1];
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double len2 = dx * dx + dy * dy;
    double t = len2 > 0.0 ? ((x[0] - a.x) * dx + (x[1] - a.y) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const double d = std::hypot(x[0] - (a.x + t * dx), x[1] - (a.y + t * dy));
    if (d < best.distance) best = {d, s, t};
  }
  return best;
}

}  // namespace

Vec2 Crack::segment_direction(std::size_t s) const {
  const double dx = points[s + 1].x - points[s].x, dy = points[s + 1].y - points[s].y;
  const double l = std::hypot(dx, dy);
  return {dx / l, dy / l};
}

double Crack::active_length() const {
  double l = 0.0;
  for (std::size_t s = 0; s < active; ++s) l += std::hypot(points[s + 1].x - points[s].x, points[s + 1].y - points[s].y);
  return l;
}

double crack_distance(const Crack& c, const double* x) { return closest(c, x).distance; }

int crack_side(const Crack& c, const double* x) {
  const Closest k = closest(c, x);
  if (c.active == 0) return 0;
  Vec2 dir = c.segment_direction(k.segment);
  // At an interior vertex the pseudo-normal (sum of the two unit directions) decides.
  if (k.t >= 1.0 && k.segment + 1 < c.active) {
    const Vec2 d2 = c.segment_direction(k.segment + 1);
    dir = {dir.x + d2.x, dir.y + d2.y};
  } else if (k.t <= 0.0 && k.segment > 0) {
    const Vec2 d0 = c.segment_direction(k.segment - 1);
    dir = {dir.x + d0.x, dir.y + d0.y};
  }
  const Vec2& a = c.points[k.segment];
  const Vec2& b = c.points[k.segment + 1];
  const double px = a.x + k.t * (b.x - a.x), py = a.y + k.t * (b.y - a.y);
  return cross(dir.x, dir.y, x[0] - px, x[1] - py) > 0.0 ? 1 : 0;
}

double crack_ramp(const Crack& c, const double* x, double* grad) {
  grad[0] = grad[1] = 0.0;
  if (!c.tip_open() || c.active == 0) return 1.0;
  const Vec2& a = c.points[c.active - 1];
  const Vec2& b = c.points[c.active];
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l = std::hypot(dx, dy);
  const double s = ((x[0] - a.x) * dx + (x[1] - a.y) * dy) / l;
  if (s <= 0.0) return 1.0;
  if (s >= l) return 0.0;
  grad[0] = -dx / (l * l);
  grad[1] = -dy / (l * l);
  return 1.0 - s / l;
}

bool segment_meets_triangle(const double* a, const double* b, const std::array<std::array<double, 2>, 3>& tri) {
  // Separating axis test: the three triangle edge normals and the segment's normal.
  auto separated = [&](double nx, double ny) {
    double tmin = std::numeric_limits<double>::infinity(), tmax = -tmin;
    for (const auto& v : tri) {
      const double p = nx * v[0] + ny * v[1];
      tmin = std::min(tmin, p);
      tmax = std::max(tmax, p);
    }
    const double pa = nx * a[0] + ny * a[1], pb = nx * b[0] + ny * b[1];
    return std::max(pa, pb) < tmin || std::min(pa, pb) > tmax;
  };
  for (int e = 0; e < 3; ++e) {
    const auto& p = tri[e];
    const auto& q = tri[(e + 1) % 3];
    if (separated(-(q[1] - p[1]), q[0] - p[0])) return false;
  }
  return !separated(-(b[1] - a[1]), b[0] - a[0]);
}

double segment_intersection(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  const double rx = q.x - p.x, ry = q.y - p.y, sx = b.x - a.x, sy = b.y - a.y;
  const double den = cross(rx, ry, sx, sy);
  if (std::abs(den) < 1e-300) return -1.0;
  const double t = cross(a.x - p.x, a.y - p.y, sx, sy) / den;
  const double u = cross(a.x - p.x, a.y - p.y, rx, ry) / den;
  if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) return -1.0;
  return t;
}

std::vector<SubTriangle> split_triangle(const std::array<std::array<double, 2>, 3>& tri,
                                        const std::vector<Crack>& cracks) {
  using Poly = std::vector<std::array<double, 2>>;
  std::vector<Poly> pieces{Poly(tri.begin(), tri.end())};
  bool cut = false;
  // A relative tolerance: a line through a vertex must not leave slivers of zero area.
  const double scale = std::max({std::abs(tri[1][0] - tri[0][0]), std::abs(tri[1][1] - tri[0][1]),
                                 std::abs(tri[2][0] - tri[0][0]), std::abs(tri[2][1] - tri[0][1])});
  const double eps = 1e-9 * scale;
  for (const Crack& c : cracks)
    for (std::size_t s = 0; s < c.active; ++s) {
      const double a[2] = {c.points[s].x, c.points[s].y};
      const double b[2] = {c.points[s + 1].x, c.points[s + 1].y};
      if (!segment_meets_triangle(a, b, tri)) continue;
      const double nx = -(b[1] - a[1]), ny = b[0] - a[0];
      const double nl = std::hypot(nx, ny);
      std::vector<Poly> next;
      for (const Poly& p : pieces) {
        Poly left, right;
        const std::size_t m = p.size();
        for (std::size_t i = 0; i < m; ++i) {
          const auto& u = p[i];
          const auto& v = p[(i + 1) % m];
          const double fu = (nx * (u[0] - a[0]) + ny * (u[1] - a[1])) / nl;
          const double fv = (nx * (v[0] - a[0]) + ny * (v[1] - a[1])) / nl;
          if (fu >= -eps) left.push_back(u);
          if (fu <= eps) right.push_back(u);
          if ((fu > eps && fv < -eps) || (fu < -eps && fv > eps)) {
            const double t = fu / (fu - fv);
            const std::array<double, 2> w{u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1])};
            left.push_back(w);
            right.push_back(w);
          }
        }
        const bool both = left.size() >= 3 && right.size() >= 3;
        if (both) cut = true;
        if (left.size() >= 3) next.push_back(left);
        if (right.size() >= 3 && both) next.push_back(right);
        if (!both && left.size() < 3) next.push_back(right);
      }
      pieces.swap(next);
    }
  std::vector<SubTriangle> out;
  if (!cut) return out;
  for (const Poly& p : pieces)
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      SubTriangle t{{p[0], p[i], p[i + 1]}};
      const double area = 0.5 * cross(t.v[1][0] - t.v[0][0], t.v[1][1] - t.v[0][1], t.v[2][0] - t.v[0][0],
                                      t.v[2][1] - t.v[0][1]);
      if (std::abs(area) > 1e-14 * scale * scale) out.push_back(t);
    }
  return out;
}

}  // namespace uhpc::micro
