#include "rcdem/solver/concrete_contacts.hpp"

#include <fmt/format.h>

#include <cstring>

#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/law_loops.hpp"
#include "rcdem/core/parallel.hpp"

namespace rcdem {

ConcreteContacts::ConcreteContacts(const Scenario& sc, const ContactNetwork& net,
                                   const Bodies& bodies, const BodyKinematics& kinematics)
    : net_(&net),
      bodies_(&bodies),
      kinematics_(&kinematics),
      law_(make_contact_law(sc.law, sc.contact)),
      body_contacts_(BodyContacts::build(net, bodies.size())) {
  contacts_.init(net, bodies.position);
  if (sc.solver.condense_elastic_contacts && condensable(law_)) {
    condensation_ = ElasticCondensation::build(net, bodies.position0);
    condensation_.held.enabled = sc.solver.hold_unloading_contacts;
    condensation_.held.softening = sc.solver.hold_softening_contacts;
    condensation_.held.intact = sc.solver.hold_intact_contacts;
  }
}

ContactInputs ConcreteContacts::inputs(const std::vector<Vec3>& positions,
                                       const std::vector<Eigen::Matrix3d>& rotation,
                                       Real dt) const {
  return {*net_,
          positions.data(),
          bodies_->position0.data(),
          bodies_->angular_velocity.data(),
          bodies_->orientation0.data(),
          rotation.data(),
          nullptr,
          dt};
}

void ConcreteContacts::evaluate(const StepContext& ctx) {
  // Evaluated from the kinematics' copy, so that what a later catch-up reads is what this
  // evaluation used; a contact condensed at the last step and visited now first has its points
  // brought up to that step from the previous kinematics.
  const BodyKinematics& k = ctx.kinematics;
  ContactInputs now = inputs(k.position, k.rotation, ctx.clock.dt);
  now.pose = k.pose.ptr();
  const ContactInputs previous = inputs(k.position_prev, k.rotation_prev, ctx.clock.dt);
  ElasticCondensation* condensed = condensation_.sums.empty() ? nullptr : &condensation_;
  energy_kept_ = ctx.report_strain_energy && condensed;  // the loop keeps them only then
  if (energy_kept_) contact_energy_.resize(static_cast<std::size_t>(net_->contact_count()));
  evaluate_contacts(law_, now, contacts_, condensed, &previous,
                    energy_kept_ ? contact_energy_.data() : nullptr);
}

void ConcreteContacts::catch_up(Real dt) const {
  // The last evaluation's kinematics: kept until the next step forms them anew.
  if (!condensation_.any_condensed) return;
  catch_up_condensed(law_, inputs(kinematics_->position, kinematics_->rotation, dt), contacts_,
                     condensation_);
}

void ConcreteContacts::distribute(const Decomposition& d, Communicator& comm) {
  comm_ = &comm;
  own_contacts_ = d.contact_offsets;
  const auto r = static_cast<std::size_t>(d.rank);
  contacts_.listed = true;
  contacts_.evaluated_blocks = d.evaluated_blocks;
  const std::vector<Index> blocks =
      Decomposition::in_blocks(d.contact_offsets, Decomposition::kContactBlock);
  contacts_.counted_begin = blocks[r];
  contacts_.counted_end = blocks[r + 1];
  energy_block_offsets_ = Decomposition::in_blocks(d.contact_offsets, Decomposition::kEnergyBlock);
  scatter_begin_ = d.sphere_offsets[r];
  scatter_spheres_end_ = d.sphere_offsets[r + 1];
  spheres_ = d.sphere_offsets.back();
}

void ConcreteContacts::scatter(Bodies& bodies) const {
  const ContactState& cs = contacts_;
  const BodyContacts& bc = body_contacts_;
  const Index n = bodies.size();
  const auto gather = [&](Index i) {
    // A body's B-side contacts belong to particles before it along the curve, some far before:
    // their forces are no longer in cache, and waiting on them was most of the gather. Requested
    // a few bodies ahead, they arrive while it sums (measured in bench/RESULTS.md). The A side
    // streams in contact order.
    constexpr Index kAhead = 6;
    if (i + kAhead < n)
      for (Index e = bc.begin[i + kAhead]; e < bc.mid[i + kAhead]; ++e) {
        __builtin_prefetch(cs.force_b[bc.entry[e]].data());
        __builtin_prefetch(cs.torque_b[bc.entry[e]].data());
      }
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (Index e = bc.begin[i]; e < bc.mid[i]; ++e) {
      const Index c = bc.entry[e];
      f += cs.force_b[c];
      t += cs.torque_b[c];
    }
    for (Index e = bc.mid[i]; e < bc.begin[i + 1]; ++e) {
      const Index c = bc.entry[e];
      f -= cs.force_b[c];
      t += cs.torque_a[c];
    }
    bodies.force[i] = f;
    bodies.torque[i] = t;
  };
  if (!comm_) {
    parallel_for(n, gather);
    return;
  }
  // Distributed: this rank's spheres, then the bodies past every sphere (the bars' cylinders).
  const Index own = scatter_spheres_end_ - scatter_begin_;
  parallel_for(own + (n - spheres_),
               [&](Index k) { gather(k < own ? scatter_begin_ + k : spheres_ + (k - own)); });
}

void ConcreteContacts::add_dissipation(StepDissipation& d) const {
  if (!contacts_.block_damage.empty()) {  // the blocked loop summed its blocks
    for (std::size_t k = 0; k < contacts_.block_damage.size(); ++k) {
      d.damage += contacts_.block_damage[k];
      d.friction += contacts_.block_friction[k];
    }
    return;
  }
  for (Index c = 0; c < net_->contact_count(); ++c) {
    d.damage += contacts_.dissipated_damage[c];
    d.friction += contacts_.dissipated_friction[c];
  }
}

void ConcreteContacts::add_strain_energy(Real& sum) const {
  // By fixed blocks of contacts on every thread, then the blocks' sums in order: the same value
  // at any thread count. A history row asks for it every few dozen steps, and serial it costs
  // about a whole step of a cracked beam (bench/RESULTS.md).
  const ContactNetwork& net = *net_;
  const BodyKinematics& k = *kinematics_;
  const bool condensed = condensation_.any_condensed;
  constexpr Index kBlock = Decomposition::kEnergyBlock;
  const Index n = net.contact_count();
  strain_energy_blocks_.assign(static_cast<std::size_t>((n + kBlock - 1) / kBlock), 0.0);
  // Distributed: this rank's blocks, then every rank's onto rank 0 (the others' sum is unused).
  std::vector<Index> own;
  if (comm_) {
    const auto r = static_cast<std::size_t>(comm_->rank());
    for (Index b = energy_block_offsets_[r]; b < energy_block_offsets_[r + 1]; ++b)
      own.push_back(b);
  }
  std::visit(
      [&](const auto& law) {
        parallel_for_listed_blocks(comm_ ? &own : nullptr, n, kBlock, [&](Index begin, Index end) {
          // Condensed contacts from their sums at the last evaluation's kinematics (their
          // histories are stale), the others from their points.
          Real e = 0.0;
          for (Index c = begin; c < end; ++c) {
            if (energy_kept_) {
              e += contact_energy_[static_cast<std::size_t>(c)];
              continue;
            }
            if (condensed && condensation_.held.held[static_cast<std::size_t>(c)]) {
              e += held_energy(c);
              continue;
            }
            e += condensed && condensation_.condensed[static_cast<std::size_t>(c)]
                     ? condensed_strain_energy(condensation_.sums, c, k.pose.ptr(),
                                               net.particle_a[c], net.particle_b[c])
                     : contacts_.strain_energy(law, net, c);
          }
          strain_energy_blocks_[static_cast<std::size_t>(begin / kBlock)] = e;
        });
      },
      law_);
  if (comm_) comm_->gather(strain_energy_blocks_, energy_block_offsets_);
  Real e = 0.0;
  for (const Real block : strain_energy_blocks_) e += block;
  sum += e;
}

Real ConcreteContacts::held_energy(Index c) const {
  // In the frame the last evaluation stored, at its poses.
  return held_strain_energy(condensation_.sums, c, condensation_.held.sums(c), contacts_.normal[c],
                            contacts_.tangent[c], kinematics_->pose.ptr(), net_->particle_a[c],
                            net_->particle_b[c]);
}

void ConcreteContacts::held_rows(HeldRows& rows) const {
  if (comm_) {
    rows = gathered_held_;
    return;
  }
  local_held_rows(0, net_->contact_count(), rows);
}

void ConcreteContacts::local_held_rows(Index lo, Index hi, HeldRows& rows) const {
  const HeldContacts& h = condensation_.held;
  if (h.held.empty()) return;  // no condensation
  const ContactNetwork& net = *net_;
  for (Index c = lo; c < hi; ++c) {
    if (const std::int16_t clock = h.softening_clock[static_cast<std::size_t>(c)]; clock != 0)
      rows.clock.push_back({c, clock});
    if (!h.held[static_cast<std::size_t>(c)]) continue;
    rows.held.push_back({c, h.sums(c)});
    // Saved by a read, or (no read since it was held) its points' histories themselves.
    const Index begin = net.point_begin[c];
    const std::vector<PlanePointState>* e =
        h.saved[static_cast<std::size_t>(c)] ? &h.entry.at(c) : nullptr;
    for (Index m = begin; m < net.point_begin[c + 1]; ++m)
      rows.entry.push_back({m, e ? (*e)[static_cast<std::size_t>(m - begin)]
                                 : contacts_.point.records[static_cast<std::size_t>(m)].history});
  }
}

namespace {

// Each rank's `local` rows appended in rank order on rank 0 (trivially copyable rows).
template <class Row>
std::vector<Row> gather_rows(Communicator& comm, const std::vector<Row>& local) {
  std::vector<std::uint8_t> bytes(local.size() * sizeof(Row)), all;
  if (!local.empty()) std::memcpy(bytes.data(), local.data(), bytes.size());
  comm.gather_bytes(bytes, all);
  std::vector<Row> rows(all.size() / sizeof(Row));
  if (!rows.empty()) std::memcpy(rows.data(), all.data(), rows.size() * sizeof(Row));
  return rows;
}

}  // namespace

void ConcreteContacts::gather_held() {
  // Each rank's own contacts (disjoint ranges, ascending by rank), held where it evaluates them.
  const auto r = static_cast<std::size_t>(comm_->rank());
  HeldRows rows;
  local_held_rows(own_contacts_[r], own_contacts_[r + 1], rows);
  gathered_held_.held = gather_rows(*comm_, rows.held);
  gathered_held_.entry = gather_rows(*comm_, rows.entry);
  gathered_held_.clock = gather_rows(*comm_, rows.clock);
}

std::string ConcreteContacts::held_rows_fault(const HeldRows& rows) const {
  if ((!rows.held.empty() || !rows.clock.empty()) && condensation_.sums.empty())
    return "contacts held where this run holds none (solver.condense_elastic_contacts off)";
  const ContactNetwork& net = *net_;
  std::size_t k = 0;
  Index last = -1;
  for (const HeldRow& w : rows.held) {
    if (w.contact <= last || w.contact >= net.contact_count())
      return fmt::format("contact {} out of range or out of order", w.contact);
    last = w.contact;
    for (Index m = net.point_begin[last]; m < net.point_begin[last + 1]; ++m, ++k)
      if (k >= rows.entry.size() || rows.entry[k].point != m)
        return fmt::format("contact {}'s entry points are not its points", last);
  }
  if (k != rows.entry.size()) return "entry points of contacts not held";
  last = -1;
  for (const SofteningClockRow& w : rows.clock) {
    if (w.contact <= last || w.contact >= net.contact_count())
      return fmt::format("clock of contact {} out of range or out of order", w.contact);
    last = w.contact;
    if (w.clock < -kSofteningBackoff || w.clock > kShortSofteningHold || w.clock == 0)
      return fmt::format("contact {}'s clock {} is not in [{}, {}] less 0", w.contact, w.clock,
                         -kSofteningBackoff, kShortSofteningHold);
  }
  return {};
}

void ConcreteContacts::apply_held_rows(const HeldRows& rows) {
  HeldContacts& h = condensation_.held;
  const ContactNetwork& net = *net_;
  std::vector<std::uint8_t> evaluated(h.block.size(), contacts_.listed ? 0 : 1);
  for (const Index b : contacts_.evaluated_blocks) evaluated[static_cast<std::size_t>(b)] = 1;
  const auto evaluated_here = [&](Index c) {
    return evaluated[static_cast<std::size_t>(c / HeldContacts::kBlock)] != 0;
  };
  std::size_t k = 0;  // held_rows_fault: the entry rows are the held contacts' points in order
  for (const HeldRow& w : rows.held) {
    const Index c = w.contact;
    const Index count = net.points_of(c);
    k += static_cast<std::size_t>(count);
    if (!evaluated_here(c)) continue;
    std::vector<PlanePointState>& e = h.entry[c];
    e.resize(static_cast<std::size_t>(count));
    for (Index m = 0; m < count; ++m)
      e[static_cast<std::size_t>(m)] = rows.entry[k - static_cast<std::size_t>(count - m)].history;
    h.sums(c) = w.sums;
    h.held[static_cast<std::size_t>(c)] = 1;
    h.saved[static_cast<std::size_t>(c)] = 1;
    if (w.sums.open_margin >= 0) restore_broken_point_sums(c, e);
  }
  for (const SofteningClockRow& w : rows.clock)
    if (evaluated_here(w.contact))
      h.softening_clock[static_cast<std::size_t>(w.contact)] = static_cast<std::int16_t>(w.clock);
  h.current = true;
}

void ConcreteContacts::restore_broken_point_sums(Index c,
                                                 const std::vector<PlanePointState>& entry) {
  // The sums hold_contact set when c entered, from its points as they were then.
  const ContactNetwork& net = *net_;
  std::vector<std::uint8_t> broken(entry.size());
  for (std::size_t m = 0; m < entry.size(); ++m) broken[m] = entry[m].damage >= 1;
  broken_point_sums(condensation_.sums, c, bodies_->position0[net.particle_a[c]],
                    contacts_.point.data(), net.point_begin[c], net.point_begin[c + 1],
                    broken.data());
}

void ConcreteContacts::visit_springs(SpringVisitor& v, const Bodies& bodies) const {
  const ContactNetwork& nw = *net_;
  std::vector<Vec3> normal(static_cast<std::size_t>(nw.contact_count()));
  for (Index c = 0; c < nw.contact_count(); ++c) {
    const Vec3 d = bodies.position0[nw.particle_b[c]] - bodies.position0[nw.particle_a[c]];
    normal[c] = Vec3(d / d.norm());
  }
  v.network(nw, std::move(normal));
}

}  // namespace rcdem
