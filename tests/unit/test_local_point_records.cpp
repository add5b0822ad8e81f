// LocalPointRecords (contact/local_point_records.hpp): each record carries its point's position and
// constants from the network, its history starts empty, the nine history values come in the
// checkpoint's order (docs/checkpoint.md), and the law's state goes in and out unchanged (with
// D written only when it changed, store_state).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "rcdem/contact/local_point_records.hpp"

namespace {

using rcdem::Index;
using rcdem::Real;

rcdem::ContactNetwork two_contacts() {
  rcdem::ContactNetwork net;
  net.particle_a = {0, 0};
  net.particle_b = {1, 2};
  net.point_begin = {0, 3, 5};
  for (int m = 0; m < 5; ++m) {
    net.point_position0.emplace_back(0.1 * m, -0.2 * m, 0.3 + m);
    net.point_area.push_back(1e-6 * (m + 1));
    net.constants.push_back({1e6 * (m + 1), 2e5 * (m + 1), 3.0 * m, 4.0 * m});
  }
  return net;
}

TEST(LocalPointRecords, InitCopiesEachPointsPositionAndConstantsWithAnEmptyHistory) {
  const rcdem::ContactNetwork net = two_contacts();
  rcdem::LocalPointRecords r;
  r.init(net);
  ASSERT_EQ(r.size(), net.point_count());
  for (Index m = 0; m < r.size(); ++m) {
    const rcdem::LocalPointRecord& p = r.data()[m];
    EXPECT_EQ(p.x0, net.point_position0[m].x());
    EXPECT_EQ(p.y0, net.point_position0[m].y());
    EXPECT_EQ(p.z0, net.point_position0[m].z());
    EXPECT_EQ(p.constants.kn, net.constants[m].kn);
    EXPECT_EQ(p.constants.ks, net.constants[m].ks);
    EXPECT_EQ(p.constants.fn_max, net.constants[m].fn_max);
    EXPECT_EQ(p.constants.c_max, net.constants[m].c_max);
    r.for_each_history(m, [](const Real& v) { EXPECT_EQ(v, 0.0); });
  }
}

TEST(LocalPointRecords, RecordsAreTwoAlignedCacheLines) {
  rcdem::LocalPointRecords r;
  r.init(two_contacts());
  EXPECT_EQ(sizeof(rcdem::LocalPointRecord), 128u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(r.data()) % 64, 0u);
  // The damage shares the first line with what the step only reads; the rest is the second line.
  const auto* base = reinterpret_cast<const char*>(r.data());
  EXPECT_LT(reinterpret_cast<const char*>(&r.data()[0].history.damage) - base, 64);
  EXPECT_GE(reinterpret_cast<const char*>(&r.data()[0].history.fn) - base, 64);
}

TEST(LocalPointRecords, HistoryComesInTheCheckpointsOrder) {
  rcdem::LocalPointRecords r;
  r.init(two_contacts());
  rcdem::PlanePointState s;
  s.fn = 1;
  s.fs = {2, 3};
  s.un = 4;
  s.us = {5, 6};
  s.un_max = 7;
  s.us_max_sq = 8;
  s.damage = 0.5;
  rcdem::store_state(r.data()[3].history, s);
  std::vector<Real> order;
  r.for_each_history(3, [&](const Real& v) { order.push_back(v); });
  EXPECT_EQ(order, (std::vector<Real>{1, 2, 3, 4, 5, 6, 7, 8, 0.5}));
  // Written through the same order (a checkpoint's load), read back as the law's state.
  Real next = 10;
  r.for_each_history(1, [&](Real& v) { v = next++; });
  const rcdem::PlanePointState t = r.data()[1].history;
  EXPECT_EQ(t.fn, 10);
  EXPECT_EQ(t.fs.x, 11);
  EXPECT_EQ(t.fs.y, 12);
  EXPECT_EQ(t.un, 13);
  EXPECT_EQ(t.us.x, 14);
  EXPECT_EQ(t.us.y, 15);
  EXPECT_EQ(t.un_max, 16);
  EXPECT_EQ(t.us_max_sq, 17);
  EXPECT_EQ(t.damage, 18);
  EXPECT_EQ(r.damage()[1], 18);
  EXPECT_EQ(r[1].fs.x(), 11);  // the world-frame view: components (t1, t2, 0)
  EXPECT_EQ(r[1].fs.z(), 0);
}

}  // namespace
