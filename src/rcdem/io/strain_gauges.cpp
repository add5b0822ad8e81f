#include "rcdem/io/strain_gauges.hpp"

#include <cmath>

namespace rcdem::io {

namespace {

// Fewer interior particles than this give no interior reading: the fit has 12 unknowns.
constexpr std::size_t kMinInteriorParticles = 12;

}  // namespace

StrainGauges::StrainGauges(const Specimen& specimen) : faces_(&specimen.boundary) {
  const BoundaryFaces& f = specimen.boundary;
  const Particles& p = specimen.particles;
  Real layer[6] = {0, 0, 0, 0, 0, 0};
  for (Index k = 0; k < f.size(); ++k) {
    const int face = f.face[k];
    layer[face] += f.area[k] * p.position[f.particle[k]][face / 2];
    area_[face] += f.area[k];
  }
  for (int a = 0; a < 3; ++a)
    if (area_[2 * a] > 0.0 && area_[2 * a + 1] > 0.0)
      gauge_length_[a] = layer[2 * a + 1] / area_[2 * a + 1] - layer[2 * a] / area_[2 * a];

  // The central region: the middle half of the specimen's box along every axis.
  const Vec3 lo = specimen.geometry.lo, size = specimen.geometry.size();
  const Vec3 inner_lo = lo + 0.25 * size, inner_hi = lo + 0.75 * size;
  for (Index i = 0; i < specimen.concrete(); ++i) {
    const Vec3& x = p.position[i];
    if ((x.array() >= inner_lo.array()).all() && (x.array() <= inner_hi.array()).all())
      interior_.push_back(i);
  }
  if (interior_.size() < kMinInteriorParticles) {
    interior_.clear();
    return;
  }
  for (const Index i : interior_) centre0_ += p.position[i];
  centre0_ /= static_cast<Real>(interior_.size());
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Index i : interior_) {
    const Vec3 d = p.position[i] - centre0_;
    m += d * d.transpose();
  }
  moment_inverse_ = m.inverse();
}

Vec3 StrainGauges::face(const Bodies& b) const {
  const BoundaryFaces& f = *faces_;
  Real sum[6] = {0, 0, 0, 0, 0, 0};
  for (Index k = 0; k < f.size(); ++k) {
    const int face = f.face[k];
    const Index i = f.particle[k];
    sum[face] += f.area[k] * (b.position[i][face / 2] - b.position0[i][face / 2]);
  }
  Vec3 e = Vec3::Zero();
  for (int a = 0; a < 3; ++a)
    if (gauge_length_[a] > 0.0)
      e[a] = (sum[2 * a + 1] / area_[2 * a + 1] - sum[2 * a] / area_[2 * a]) / gauge_length_[a];
  return e;
}

Vec3 StrainGauges::interior(const Bodies& b) const {
  if (interior_.empty()) return Vec3::Zero();
  // G = (sum u X^T) M^-1 over the centred initial positions X (sum X = 0, so u need not be
  // centred).
  Eigen::Matrix3d ux = Eigen::Matrix3d::Zero();
  for (const Index i : interior_)
    ux += (b.position[i] - b.position0[i]) * (b.position0[i] - centre0_).transpose();
  const Eigen::Matrix3d g = ux * moment_inverse_;
  return g.diagonal();
}

nlohmann::ordered_json StrainGauges::summary() const {
  // Built key by key: a nested brace list leaves nlohmann to guess object or array.
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  j["face_gauge_length_m"] = {gauge_length_.x(), gauge_length_.y(), gauge_length_.z()};
  j["face_area_m2"] = {area_[0], area_[1], area_[2], area_[3], area_[4], area_[5]};
  j["interior_particles"] = interior_.size();
  return j;
}

}  // namespace rcdem::io
