#pragma once
// For verification tests: small elastic specimens, and their generalised forces and tangent
// stiffness built from the solver's own contact and plate routines (EL law), to compare the
// dynamic solver with statics and the time-step estimate with the assembly's eigenvalues.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/laws/elastic.hpp"
#include "rcdem/solver/plates.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem::test {

// Glued platens on the box's bottom and top faces (TOML tables); `top` adds keys to the top one.
inline std::string glued_platens(const std::string& top = "") {
  return "[plates.bottom]\nface = \"z-\"\nglued = true\n[plates.top]\nface = \"z+\"\nglued = "
         "true\n" +
         top;
}

// An elastic (EL) box of edge `size` with k_s = alpha k_n, undamped unless asked; `extra` goes
// into its [solver] table and may add tables after it (plates). The solver's plain set-up
// (preset "basic") unless `extra` says otherwise: these tests are about the solver itself.
inline Scenario elastic_box(Real size, const std::string& extra = "", Real damping = 0.0,
                            Real alpha = 0.3) {
  return parse_scenario(fmt::format(R"(
[specimen]
shape = "box"
size = [{0}, {0}, {0}]
[generation]
seed = 3
relaxation_iterations = 100
[contact]
law = "EL"
alpha = {3}
[solver]
preset = "basic"
damping = {1}
{2}
)",
                                    size, damping, extra, alpha),
                        "elastic_box.toml");
}

// Generalised forces (force, torque per body) of the contacts and plates at displacements q
// (translation, rotation vector per body) from the initial state, the top plate moved by delta;
// built from the solver's own contact and plate routines.
struct StaticModel {
  const ContactNetwork* net;
  Bodies b0;
  std::vector<Plate> plates0;
  PlateContacts pc0;
  std::size_t top;

  Eigen::VectorXd forces(const Eigen::VectorXd& q, Real delta, Real* reaction = nullptr) const {
    Bodies b = b0;
    for (Index i = 0; i < b.size(); ++i) {
      b.position[i] = b0.position0[i] + q.segment<3>(6 * i);
      const Vec3 r = q.segment<3>(6 * i + 3);
      b.orientation[i] =
          r.norm() > 0 ? Quat(Eigen::AngleAxis<Real>(r.norm(), r.normalized())) : Quat::Identity();
    }
    ContactState cs;
    cs.init(*net, b0.position0);
    evaluate_contacts(Elastic{}, *net, b, cs, 1e-7);
    std::vector<Plate> plates = plates0;
    plates[top].displacement = delta;
    PlateContacts pc = pc0;
    evaluate_plate_contacts(plates, pc, b);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(6 * b.size());
    for (Index c = 0; c < net->contact_count(); ++c) {
      const Index a = net->particle_a[c], bb = net->particle_b[c];
      f.segment<3>(6 * a) -= cs.force_b[c];
      f.segment<3>(6 * bb) += cs.force_b[c];
      f.segment<3>(6 * a + 3) += cs.torque_a[c];
      f.segment<3>(6 * bb + 3) += cs.torque_b[c];
    }
    for (Index k = 0; k < pc.size(); ++k) {
      f.segment<3>(6 * pc.particle[k]) += pc.force[k];
      f.segment<3>(6 * pc.particle[k] + 3) += pc.torque[k];
    }
    if (reaction) *reaction = plates[top].force.z();
    return f;
  }

  // The tangent stiffness at q = 0 (plates at rest) by central differences of forces().
  Eigen::MatrixXd tangent_stiffness() const {
    const Index n = 6 * b0.size();
    Eigen::MatrixXd K(n, n);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    for (Index j = 0; j < n; ++j) {
      const Real h = (j % 6) < 3 ? 1e-9 : 1e-7;
      Eigen::VectorXd qp = zero, qm = zero;
      qp[j] = h;
      qm[j] = -h;
      K.col(j) = -(forces(qp, 0.0) - forces(qm, 0.0)) / (2 * h);
    }
    return K;
  }
};

}  // namespace rcdem::test
