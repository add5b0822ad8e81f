#pragma once
// For each body, the contacts it takes part in (CSR), so that forces are gathered per body in a
// fixed order: no atomics, and the same sum whatever the thread count (DESIGN principle 3).
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// Body i's contacts: entry[begin[i], mid[i]) those where it is B, then entry[mid[i], begin[i+1])
// those where it is A, each in contact order. Two runs instead of a side bit per entry: the gather
// then has no branch per contact, which mispredicted at every change of side and held back the
// loads behind it (the gather was a fifth of an elastic step). The networks are built with A < B
// and numbered by A, so a body's B-side contacts come before its own: the same order as one run
// in contact order.
struct BodyContacts {
  std::vector<Index> begin;  // size bodies + 1
  std::vector<Index> mid;    // size bodies
  std::vector<Index> entry;  // contact indices

  static BodyContacts build(const ContactNetwork& net, Index bodies) {
    BodyContacts bc;
    const auto n = static_cast<std::size_t>(bodies);
    bc.begin.assign(n + 1, 0);
    std::vector<Index> as_b(n, 0);
    for (Index c = 0; c < net.contact_count(); ++c) {
      ++bc.begin[net.particle_a[c] + 1];
      ++bc.begin[net.particle_b[c] + 1];
      ++as_b[net.particle_b[c]];
    }
    for (Index i = 0; i < bodies; ++i) bc.begin[i + 1] += bc.begin[i];
    bc.mid.resize(n);
    for (Index i = 0; i < bodies; ++i) bc.mid[i] = bc.begin[i] + as_b[i];
    bc.entry.resize(static_cast<std::size_t>(bc.begin.back()));
    std::vector<Index> fill_b(bc.begin.begin(), bc.begin.end() - 1), fill_a(bc.mid);
    for (Index c = 0; c < net.contact_count(); ++c) {
      bc.entry[fill_a[net.particle_a[c]]++] = c;
      bc.entry[fill_b[net.particle_b[c]]++] = c;
    }
    return bc;
  }
};

}  // namespace rcdem
