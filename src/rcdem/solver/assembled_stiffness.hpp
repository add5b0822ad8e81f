#pragma once
// The stiffness of the whole assembly, every body and every spring at once (SPEC 6's better time
// step), as an operator: y = A x with A = M^-1/2 K M^-1/2 on the bodies' generalised
// displacements (6 per body: translation of the centre, then rotation vector; world frame). Its
// largest eigenvalue is omega_max^2 (solver/critical_time_step.hpp).
//
// K is the initial tangent stiffness of the springs that body_stiffness.hpp reads one body at a
// time: a spring S = k_n n n^T + k_s (I - n n^T) joining a point on body a (arm r_a from its
// centre) to a point on body b (arm r_b) stretches by u = B_b x_b - B_a x_a with B = [I, -[r x]],
// and adds B^T S B to the assembly; rotational springs (an interaction node's bending and
// torsion) add their 3x3 block on the two rotations. The matrix is never formed: a network's
// springs are its local points, read from the network itself.
#include <vector>

#include "rcdem/solver/body_contacts.hpp"
#include "rcdem/solver/body_stiffness.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

class AssembledStiffness {
 public:
  // The bodies' masses, principal inertia and orientation set M; their centres at t = 0 the arms.
  explicit AssembledStiffness(const Bodies& bodies);

  // Every local point of `net` as a spring between its contact's two bodies, with the contact's
  // unit normal normal[c]. The network must outlive this operator.
  void add_network(const ContactNetwork& net, std::vector<Vec3> normal);
  // One spring; a < 0 ties body b's point to the ground (a fixed plate).
  void add_spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b, const Vec3& n, Real kn,
                  Real ks);
  // A rotational spring k (world frame) on the rotation of b relative to a.
  void add_rotational(Index a, Index b, const Mat3& k);

  Index size() const { return 6 * bodies_; }
  // y = A x, both of size(). The result does not depend on the thread count.
  void apply(const Real* x, Real* y) const;

 private:
  struct Network {
    const ContactNetwork* net;
    std::vector<Vec3> normal;
    BodyContacts per_body;
  };
  struct Spring {
    Index a, b;
    Vec3 arm_a, arm_b, n;
    Real kn, ks;
  };
  struct Rotational {
    Index a, b;
    Mat3 k;
  };
  Index bodies_;
  std::vector<Vec3> centre0_;
  std::vector<Real> inv_sqrt_mass_;
  std::vector<Mat3> inv_sqrt_inertia_;  // world frame
  std::vector<Network> networks_;
  std::vector<Spring> springs_;
  std::vector<Rotational> rotational_;
  // Work space of apply(): the scaled displacements, each contact's force and moments, and each
  // body's sums (K z).
  mutable std::vector<Vec3> zt_, zr_, body_force_, body_moment_;
  mutable std::vector<Vec3> contact_force_, contact_moment_a_, contact_moment_b_;
};

}  // namespace rcdem
