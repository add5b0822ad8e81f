#pragma once
// Basic numeric types shared by every part of rcdem. Positions and displacements stay double:
// a 700 mm beam resolved to micrometre crack openings needs more than float's 7 digits.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace rcdem {

using Real = double;
using Index = std::int64_t;
using Vec3 = Eigen::Matrix<Real, 3, 1>;

inline constexpr Real kPi = 3.14159265358979323846;

}  // namespace rcdem
