#include "rcdem/solver/concrete_contacts.hpp"

namespace rcdem {

ConcreteContacts ConcreteContacts::build(const Scenario& sc, const ContactNetwork& net,
                                         const Bodies& bodies) {
  ConcreteContacts c;
  c.law = make_contact_law(sc.law, sc.contact);
  c.contacts.init(net, bodies.position);
  if (sc.solver.condense_elastic_contacts && condensable(c.law))
    c.condensation = ElasticCondensation::build(net, bodies.position0);
  c.body_contacts = BodyContacts::build(net, bodies.size());
  const auto n = static_cast<std::size_t>(bodies.size());
  c.rotation.assign(n, Eigen::Matrix3d::Identity());
  c.rotation_prev = c.rotation;
  c.position_eval = bodies.position;
  c.position_prev = bodies.position;
  c.pose.resize(bodies.size());
  return c;
}

}  // namespace rcdem
