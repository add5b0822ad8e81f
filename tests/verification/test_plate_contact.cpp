// One particle against an unglued, frictionless rigid plate of finite extent (SPEC 6,
// solver/plates.cpp), moved by hand: the contact is unilateral with k_n along the plate's normal;
// a point that reaches the rectangle across its edge, already below the plate's plane, starts from
// zero force; a loaded contact that slides off the rectangle books the energy its spring held as
// lost. Together these keep the energy ledger closed at the plates' edges.
#include <gtest/gtest.h>

#include <cmath>

#include "rcdem/solver/plates.hpp"
#include "rcdem/state/bodies.hpp"

using namespace rcdem;

namespace {

constexpr Real kKn = 2.0e8;  // N/m

struct OnePlate {
  std::vector<Plate> plates;
  PlateContacts pc;
  Bodies b;

  OnePlate() {
    Plate p;
    p.name = "support";
    p.axis = 2;
    p.side = -1;
    p.normal = Vec3::UnitZ();  // into the specimen, which lies above z = 0
    p.face_coordinate = 0.0;
    p.u_min = 0.0;  // x
    p.u_max = 0.01;
    p.v_min = -1.0;  // y
    p.v_max = 1.0;
    plates.push_back(p);
    // A particle centred 4 mm above the face, its face point 1 mm outside the rectangle.
    add_body(b, Vec3(0.011, 0.0, 0.004), 1e-3, Vec3(1e-9, 1e-9, 1e-9), Quat::Identity(), 0.004);
    pc.plate = {0};
    pc.particle = {0};
    pc.point0 = {Vec3(0.011, 0.0, 0.0)};
    pc.constants = {{kKn, 0.3 * kKn, 0.0, 0.0}};
    pc.state.assign(1, LocalPointState{});
    pc.force.assign(1, Vec3::Zero());
    pc.torque.assign(1, Vec3::Zero());
    pc.strain_energy.assign(1, 0.0);
    pc.dissipated_friction.assign(1, 0.0);
    pc.active.assign(1, 0);
    pc.entry_opening.assign(1, 0.0);
  }
  // Moves the particle by (dx, 0, dz) from its initial place and evaluates the contact.
  void at(Real dx, Real dz) {
    b.position[0] = b.position0[0] + Vec3(dx, 0.0, dz);
    evaluate_plate_contacts(plates, pc, b);
  }
};

}  // namespace

TEST(PlateContact, EntersAcrossTheEdgeWithoutAnImpulseAndBooksWhatItReleases) {
  OnePlate s;
  const Real sink = 1e-5;
  // Outside the rectangle and 10 um below the plate's plane: no contact.
  s.at(0.0, -sink);
  EXPECT_EQ(s.pc.active[0], 0);
  EXPECT_EQ(s.pc.force[0].norm(), 0.0);
  // Slid onto the rectangle at that depth: active, but no force and no energy yet.
  s.at(-0.002, -sink);
  EXPECT_EQ(s.pc.active[0], 1);
  EXPECT_NEAR(s.pc.entry_opening[0], -sink, 1e-18);
  EXPECT_NEAR(s.pc.force[0].norm(), 0.0, 1e-9);
  EXPECT_NEAR(s.pc.strain_energy[0], 0.0, 1e-20);
  // Pressed 2 um further: the plate pushes up with k_n x 2 um.
  const Real press = 2e-6;
  s.at(-0.002, -sink - press);
  EXPECT_NEAR(s.pc.force[0].z(), kKn * press, 1e-9 * kKn * press);
  EXPECT_NEAR(s.plates[0].force.z(), -kKn * press, 1e-9 * kKn * press);
  const Real held = 0.5 * kKn * press * press;
  EXPECT_NEAR(s.pc.strain_energy[0], held, 1e-12 * held);
  // Slid off the rectangle while pressed: the force ends and its energy is booked as lost.
  s.at(0.0, -sink - press);
  EXPECT_EQ(s.pc.active[0], 0);
  EXPECT_EQ(s.pc.force[0].norm(), 0.0);
  EXPECT_EQ(s.pc.strain_energy[0], 0.0);
  EXPECT_NEAR(s.pc.dissipated_friction[0], held, 1e-12 * held);
  // A face meeting the plate face-on starts at zero opening, as before.
  s.at(-0.002, 1e-6);
  EXPECT_EQ(s.pc.active[0], 0);
  s.at(-0.002, -press);
  EXPECT_EQ(s.pc.active[0], 1);
  EXPECT_EQ(s.pc.entry_opening[0], 0.0);
  EXPECT_NEAR(s.pc.force[0].z(), kKn * press, 1e-9 * kKn * press);
  EXPECT_EQ(s.pc.dissipated_friction[0], 0.0);
  // Lifted off: separated, nothing held, the small energy it held released as lost.
  s.at(-0.002, 1e-6);
  EXPECT_EQ(s.pc.active[0], 0);
  EXPECT_NEAR(s.pc.dissipated_friction[0], held, 1e-12 * held);
}
