#pragma once
// The stiffness each body feels from its own springs, as one symmetric 6x6 block (translation of
// its centre, rotation about it; world frame), and SPEC 6's time step sqrt(m / sum k) read from
// it: 1 / sqrt(lambda_max) of the block scaled by the body's mass and inertia, M^-1/2 K M^-1/2.
//
// Why a block and not the scalar sum of SPEC 6 taken literally: a local point's spring is k_n
// along the contact normal and k_s = alpha k_n across it (SPEC (3)-(4)), and a body's springs
// point every way, so the scalar sum of max(k_n, k_s) over-counts the stiffness of any one motion
// about 1.9x (alpha = 0.3: the block's largest eigenvalue is near (k_n + 2 k_s) / 3 per spring),
// and the sums per principal axis of rotation ignore that a motion can be part translation,
// part rotation. The block is the body's exact stiffness with its neighbours held; neighbours
// moving against it can raise the highest frequency of the assembly by up to 2x in lambda
// (sqrt 2 in time step), which SPEC 6's safety <= 0.5 covers (docs/model.md 4).
#include <Eigen/Dense>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

using Mat3 = Eigen::Matrix<Real, 3, 3>;
using Mat6 = Eigen::Matrix<Real, 6, 6>;

class BodyStiffness {
 public:
  explicit BodyStiffness(Index bodies) : k_(static_cast<std::size_t>(bodies), Mat6::Zero()) {}

  // A spring acting at `arm` from body i's centre with stiffness S = k_n n n^T + k_s (I - n n^T)
  // (n unit): a motion (dx, dtheta) of the body moves the spring's end by u = dx + dtheta x arm,
  // so the block gains B^T S B with B = [I, -[arm x]].
  void add_spring(Index i, const Vec3& n, Real kn, Real ks, const Vec3& arm);

  // A rotational spring (an interaction node's bending and torsion), world frame.
  void add_rotational(Index i, const Mat3& k);

  struct Limit {
    Real time_step;  // 1 / sqrt(lambda_max); infinite for a body without springs
    bool rotation;   // the fastest motion is more rotation than translation (mass-scaled)
    int body_axis;   // for a rotation: the principal axis it turns about most (0, 1, 2)
  };
  // For body i of mass m and principal moments `inertia` about the columns of `axes` (world).
  Limit limit(Index i, Real mass, const Vec3& inertia, const Mat3& axes) const;

 private:
  std::vector<Mat6> k_;
};

}  // namespace rcdem
