#pragma once
// Every body's centre and orientation packed in one 64-byte cache line (x, y, z, qw, qx, qy, qz,
// unused), formed once per step for the condensed contacts' SIMD kernel
// (contact/elastic_condensation.cpp). The kernel gathers both ends of 8 contacts at a time: from
// separate centre and rotation-matrix arrays that was 24 gathers touching ~3 cache lines per body,
// and the gathers were half the kernel; from a pose it is 14 gathers from one line, and the
// rotation matrix is rebuilt in the lanes (rotation_from_quaternion below).
#include <cstddef>
#include <new>
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

// std::allocator aligns to 16 bytes and Eigen::aligned_allocator to the vector width (16-64
// bytes, by the build's ISA): a pose must not straddle two cache lines on any build.
template <typename T, std::size_t kAlign>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <typename U>
  AlignedAllocator(const AlignedAllocator<U, kAlign>&) {}
  template <typename U>
  struct rebind {
    using other = AlignedAllocator<U, kAlign>;
  };
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{kAlign}));
  }
  void deallocate(T* p, std::size_t) { ::operator delete (p, std::align_val_t{kAlign}); }
  friend bool operator==(const AlignedAllocator&, const AlignedAllocator&) { return true; }
  friend bool operator!=(const AlignedAllocator&, const AlignedAllocator&) { return false; }
};

struct BodyPoses {
  static constexpr Index kStride = 8;  // doubles per body: one cache line
  std::vector<Real, AlignedAllocator<Real, 64>> data;

  void resize(Index bodies) { data.assign(static_cast<std::size_t>(kStride * bodies), 0.0); }
  void set(Index i, const Vec3& x, const Quat& q) {
    Real* p = data.data() + kStride * i;
    p[0] = x.x();
    p[1] = x.y();
    p[2] = x.z();
    p[3] = q.w();
    p[4] = q.x();
    p[5] = q.y();
    p[6] = q.z();
  }
  // All bodies at once (tests, and callers without a step loop of their own).
  static BodyPoses of(const std::vector<Vec3>& x, const std::vector<Quat>& q) {
    BodyPoses p;
    p.resize(static_cast<Index>(x.size()));
    for (std::size_t i = 0; i < x.size(); ++i) p.set(static_cast<Index>(i), x[i], q[i]);
    return p;
  }
  const Real* ptr() const { return data.data(); }
};

// The rotation matrix of a unit quaternion, column-major (r[i + 3 j] = R(i, j)), with Eigen's
// toRotationMatrix() arithmetic: plain scalars, so that it runs in SIMD lanes. Rounding may differ
// from Eigen's by the fusing of multiply-adds; the two paths of a contact agree to the rounding of
// its offset displacement either way (test_elastic_condensation.cpp).
[[gnu::always_inline]] inline void rotation_from_quaternion(Real w, Real x, Real y, Real z,
                                                            Real (&r)[9]) {
  const Real tx = 2 * x, ty = 2 * y, tz = 2 * z;
  const Real twx = tx * w, twy = ty * w, twz = tz * w;
  const Real txx = tx * x, txy = ty * x, txz = tz * x;
  const Real tyy = ty * y, tyz = tz * y, tzz = tz * z;
  r[0] = 1 - (tyy + tzz);
  r[1] = txy + twz;
  r[2] = txz - twy;
  r[3] = txy - twz;
  r[4] = 1 - (txx + tzz);
  r[5] = tyz + twx;
  r[6] = txz + twy;
  r[7] = tyz - twx;
  r[8] = 1 - (txx + tyy);
}

}  // namespace rcdem
