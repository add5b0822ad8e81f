#include "rcdem/tessellation/facet_area_split.hpp"

namespace rcdem {

FacetSplit split_facet_area(std::span<const Vec3> v) {
  FacetSplit s;
  const std::size_t n = v.size();
  s.vertex_area.assign(n, 0.0);
  if (n < 3) return s;

  Vec3 newell = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) newell += v[i].cross(v[(i + 1) % n]);
  const Real twice_area = newell.norm();
  if (twice_area == 0.0) return s;
  s.normal = newell / twice_area;

  // Area centroid by a fan from the vertex mean (inside a convex polygon).
  Vec3 mean = Vec3::Zero();
  for (const auto& p : v) mean += p;
  mean /= static_cast<Real>(n);
  Vec3 weighted = Vec3::Zero();
  Real total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % n];
    const Real t = 0.5 * (a - mean).cross(b - mean).dot(s.normal);
    weighted += t * (mean + a + b) / 3.0;
    total += t;
  }
  s.centroid = weighted / total;

  // (S1): fan from the centroid, a third of each triangle to each of its corners.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Real t = 0.5 * (v[i] - s.centroid).cross(v[j] - s.centroid).dot(s.normal);
    s.area += t;
    s.centroid_area += t / 3.0;
    s.vertex_area[i] += t / 3.0;
    s.vertex_area[j] += t / 3.0;
  }
  return s;
}

std::vector<Vec3> merge_close_vertices(std::span<const Vec3> v, Real tolerance) {
  std::vector<Vec3> out;
  out.reserve(v.size());
  for (const auto& p : v)
    if (out.empty() || (p - out.back()).norm() > tolerance) out.push_back(p);
  while (out.size() > 1 && (out.front() - out.back()).norm() <= tolerance) out.pop_back();
  return out;
}

}  // namespace rcdem
