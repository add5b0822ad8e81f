#include "rcdem/config/bar_path.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {

// The arc rounding the corner p between the legs from `prev` and to `next`: its points from the
// tangent point on the incoming leg to the one on the outgoing leg (p itself if straight).
void add_bend(const Vec3& prev, const Vec3& p, const Vec3& next, Real radius, Real max_turn,
              const std::string& where, std::vector<Vec3>& out) {
  const Vec3 a = (p - prev).normalized(), b = (next - p).normalized();
  const Real turn = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
  if (turn < 1e-9) {
    out.push_back(p);
    return;
  }
  if (turn > kPi - 1e-6)
    fail("{}: the bar turns back on itself at ({}, {}, {}) m", where, p.x(), p.y(), p.z());
  const Real t = radius * std::tan(0.5 * turn);  // from the corner to each tangent point
  if (t > 0.5 * (p - prev).norm() * (1.0 + 1e-12) || t > 0.5 * (next - p).norm() * (1.0 + 1e-12))
    fail(
        "{}: the bend at ({}, {}, {}) m needs {:.4g} m of each leg for its radius {:.4g} m; "
        "expected legs at least twice that long, or a smaller bend_radius",
        where, p.x(), p.y(), p.z(), t, radius);
  const Vec3 inward = (b - a.dot(b) * a).normalized();
  const Vec3 centre = p - t * a + radius * inward;
  const auto m = static_cast<int>(std::ceil(turn / max_turn - 1e-9));
  for (int k = 0; k <= m; ++k) {
    const Real phi = turn * k / m;
    out.push_back(centre - radius * std::cos(phi) * inward + radius * std::sin(phi) * a);
  }
}

}  // namespace

std::vector<Vec3> bar_centreline(const std::vector<Vec3>& corners, bool closed, Real radius,
                                 const std::string& where, Real max_turn) {
  const std::size_t n = corners.size();
  if (n < (closed ? 3U : 2U))
    fail("{}: expected at least {} points", where, closed ? 3 : 2);
  for (std::size_t i = 0; i < n; ++i)
    if ((corners[(i + 1) % n] - corners[i]).norm() <= 0.0 && (closed || i + 1 < n))
      fail("{}: points {} and {} coincide", where, i, (i + 1) % n);
  std::vector<Vec3> raw;
  if (!closed) raw.push_back(corners.front());
  for (std::size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); ++i)
    add_bend(corners[(i + n - 1) % n], corners[i], corners[(i + 1) % n], radius, max_turn, where,
             raw);
  if (!closed) raw.push_back(corners.back());
  // Legs used up by their bends leave two coincident points: keep one.
  std::vector<Vec3> out;
  const Real tiny = 1e-9 * std::max(radius, 1e-3);
  for (const Vec3& p : raw)
    if (out.empty() || (p - out.back()).norm() > tiny) out.push_back(p);
  if (closed && out.size() > 1 && (out.back() - out.front()).norm() <= tiny) out.pop_back();
  return out;
}

}  // namespace rcdem
