#include "rcdem/solver/bar_interface.hpp"

#include <algorithm>

#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/law_loops.hpp"
#include "rcdem/tessellation/interface_network_builder.hpp"

namespace rcdem {

BarInterface::BarInterface(std::size_t index, const BarSettings& settings, const ContactParameters& contact,
                           const InterfaceContacts& ic, const Bodies& bodies)
    : index_(index),
      ic_(&ic),
      law_(make_contact_law(settings.interface == InterfaceLaw::EL
                                ? "EL"
                                : settings.interface_softening,
                            interface_parameters(contact, settings),
                            "bars.*.interface_softening")) {
  std::vector<Vec3> axes(ic.anchor0.size());
  for (std::size_t c = 0; c < axes.size(); ++c)
    axes[c] = bodies.orientation0[ic.net.particle_b[c]] * Vec3::UnitZ();
  state_.init(ic.net, bodies.position, &ic.anchor0, &axes);
}

Index BarInterface::task_count() const {
  return (ic_->net.contact_count() + kTaskSize - 1) / kTaskSize;
}

void BarInterface::run_task(Index task, const StepContext& ctx) {
  const Index begin = task * kTaskSize;
  const Index end = std::min(ic_->net.contact_count(), begin + kTaskSize);
  const ContactInputs in = body_inputs(ic_->net, ctx.bodies, ctx.kinematics.rotation.data(),
                                       ic_->anchor0.data(), ctx.clock.dt);
  evaluate_contact_range(law_, in, state_, begin, end);
}

void BarInterface::scatter(Bodies& bodies) const {
  const ContactNetwork& nw = ic_->net;
  for (Index c = 0; c < nw.contact_count(); ++c) {
    bodies.force[nw.particle_b[c]] += state_.force_b[c];
    bodies.torque[nw.particle_b[c]] += state_.torque_b[c];
    bodies.force[nw.particle_a[c]] -= state_.force_b[c];
    bodies.torque[nw.particle_a[c]] += state_.torque_a[c];
  }
}

void BarInterface::add_dissipation(StepDissipation& d) const {
  for (std::size_t c = 0; c < state_.dissipated_damage.size(); ++c) {
    d.damage += state_.dissipated_damage[c];
    d.friction += state_.dissipated_friction[c];
  }
}

void BarInterface::add_strain_energy(Real& sum) const {
  sum += std::visit(
      [&](const auto& l) {
        Real e = 0.0;
        for (Index c = 0; c < ic_->net.contact_count(); ++c)
          e += state_.strain_energy(l, ic_->net, c);
        return e;
      },
      law_);
}

void BarInterface::visit_springs(SpringVisitor& v, const Bodies& bodies) const {
  // The normal across the cylinder's axis through the interface sphere.
  const ContactNetwork& nw = ic_->net;
  std::vector<Vec3> n(static_cast<std::size_t>(nw.contact_count()));
  for (Index c = 0; c < nw.contact_count(); ++c) {
    const Vec3 axis = bodies.orientation0[nw.particle_b[c]] * Vec3::UnitZ();
    const Vec3 d = bodies.position0[nw.particle_a[c]] - ic_->anchor0[c];
    const Vec3 across = d - d.dot(axis) * axis;
    n[c] = Vec3(across / across.norm());
  }
  v.network(nw, std::move(n));
}

}  // namespace rcdem
