// The gather's per-body contact lists (solver/body_contacts.hpp): every contact appears once on
// each of its two bodies, a body's B-side contacts first and then its A-side ones, each run in
// contact order. With a network numbered by A (the builder's order) that is the contact order, so
// the gather sums each body's forces in the same order as one pass over its contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "rcdem/core/rng.hpp"
#include "rcdem/solver/body_contacts.hpp"

using namespace rcdem;

namespace {

// A random network of `contacts` pairs a < b among `bodies` bodies, numbered by A, then B.
ContactNetwork random_network(Index bodies, Index contacts, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<std::pair<Index, Index>> pairs;
  while (static_cast<Index>(pairs.size()) < contacts) {
    const auto a = static_cast<Index>(rng.uniform() * static_cast<Real>(bodies - 1));
    const Index b = a + 1 + static_cast<Index>(rng.uniform() * static_cast<Real>(bodies - 1 - a));
    if (b < bodies) pairs.emplace_back(a, b);
  }
  std::sort(pairs.begin(), pairs.end());
  ContactNetwork net;
  for (const auto& [a, b] : pairs) {
    net.particle_a.push_back(a);
    net.particle_b.push_back(b);
  }
  return net;
}

}  // namespace

TEST(BodyContacts, ListsEachContactOnBothBodiesBSideFirstInContactOrder) {
  const Index bodies = 300;
  const ContactNetwork net = random_network(bodies, 2000, 11);
  const BodyContacts bc = BodyContacts::build(net, bodies + 2);  // two bodies with no contact
  ASSERT_EQ(bc.begin.size(), static_cast<std::size_t>(bodies + 3));
  ASSERT_EQ(bc.entry.size(), 2 * net.particle_a.size());
  for (Index i = 0; i < bodies + 2; ++i) {
    // What one pass over the contacts in order finds for body i, and on which side.
    std::vector<Index> as_b, as_a, in_order;
    for (Index c = 0; c < net.contact_count(); ++c) {
      if (net.particle_b[c] == i) as_b.push_back(c);
      if (net.particle_a[c] == i) as_a.push_back(c);
      if (net.particle_a[c] == i || net.particle_b[c] == i) in_order.push_back(c);
    }
    ASSERT_LE(bc.begin[i], bc.mid[i]);
    ASSERT_LE(bc.mid[i], bc.begin[i + 1]);
    const std::vector<Index> b_side(bc.entry.begin() + bc.begin[i], bc.entry.begin() + bc.mid[i]);
    const std::vector<Index> a_side(bc.entry.begin() + bc.mid[i],
                                    bc.entry.begin() + bc.begin[i + 1]);
    EXPECT_EQ(b_side, as_b) << "body " << i;
    EXPECT_EQ(a_side, as_a) << "body " << i;
    // Numbered by A with A < B: B's runs then A's is the contact order.
    std::vector<Index> both = b_side;
    both.insert(both.end(), a_side.begin(), a_side.end());
    EXPECT_EQ(both, in_order) << "body " << i;
  }
}
