#include "rcdem/solver/body_stiffness.hpp"

#include <cmath>
#include <limits>

namespace rcdem {

namespace {
Mat3 cross_matrix(const Vec3& r) {
  Mat3 m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}
}  // namespace

void BodyStiffness::add_spring(Index i, const Vec3& n, Real kn, Real ks, const Vec3& arm) {
  const Mat3 s = ks * Mat3::Identity() + (kn - ks) * n * n.transpose();
  // dtheta x arm = -[arm x] dtheta.
  const Mat3 r = cross_matrix(arm);
  const Mat3 sr = s * r;
  Mat6& k = k_[static_cast<std::size_t>(i)];
  k.topLeftCorner<3, 3>() += s;
  k.topRightCorner<3, 3>() -= sr;
  k.bottomLeftCorner<3, 3>() -= sr.transpose();
  k.bottomRightCorner<3, 3>() += r.transpose() * sr;
}

void BodyStiffness::add_rotational(Index i, const Mat3& kr) {
  k_[static_cast<std::size_t>(i)].bottomRightCorner<3, 3>() += kr;
}

BodyStiffness::Limit BodyStiffness::limit(Index i, Real mass, const Vec3& inertia,
                                          const Mat3& axes) const {
  // M^-1/2 = blockdiag(m^-1/2 I, Q diag(I_e^-1/2) Q^T).
  Mat6 w = Mat6::Zero();
  w.topLeftCorner<3, 3>() = Mat3::Identity() / std::sqrt(mass);
  w.bottomRightCorner<3, 3>() =
      axes * inertia.cwiseSqrt().cwiseInverse().asDiagonal() * axes.transpose();
  const Mat6& k = k_[static_cast<std::size_t>(i)];
  if (k.isZero(0.0)) return {std::numeric_limits<Real>::infinity(), false, 0};  // no spring
  const Mat6 a = w * k * w;
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(a);
  const Real lambda = eig.eigenvalues()[5];
  // A block too stiff for its mass to be resolved in doubles (a modulus of 1e200: the solver's
  // squared norms overflow) has no usable step: 0, which the caller refuses.
  if (!std::isfinite(lambda) || !a.allFinite()) return {0.0, false, 0};
  if (!(lambda > 0.0)) return {std::numeric_limits<Real>::infinity(), false, 0};
  const Eigen::Matrix<Real, 6, 1> v = eig.eigenvectors().col(5);
  Limit out{1.0 / std::sqrt(lambda), v.tail<3>().squaredNorm() > v.head<3>().squaredNorm(), 0};
  (axes.transpose() * v.tail<3>()).cwiseAbs().maxCoeff(&out.body_axis);
  return out;
}

}  // namespace rcdem
