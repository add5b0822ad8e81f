#pragma once
// Strain gauges on a specimen (docs/model.md 7): what a run reports as strain_* and
// interior_strain_* in history.csv, and what `rcdem calibrate` reads E and nu from.
//
// Face gauge: the mean displacement of the particles touching a face (weighted by their boundary
// areas), high face minus low, over the distance between those two particle layers at t = 0 (the
// true gauge length). The layers' centres sit about one particle radius inside the faces, so
// dividing by the side instead under-reads the strain by 2 x depth / side (E 5% high on a 160 mm
// cube, 10% on an 80 mm one).
//
// Interior gauge: the least-squares affine fit u(x) = u0 + G (x - x0) to the displacements of the
// concrete particles in the specimen's central region (the middle half of each side), away from
// the faces and the platens' end restraint; strain_a = G_aa.
#include <nlohmann/json.hpp>
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem::io {

class StrainGauges {
 public:
  explicit StrainGauges(const Specimen& specimen);

  // Normal strains along x, y, z from the face gauges (0 on an axis without two gauged faces).
  Vec3 face(const Bodies& b) const;
  // Normal strains from the interior fit (0 if the central region holds too few particles).
  Vec3 interior(const Bodies& b) const;

  // The distance between the two particle layers per axis at t = 0 (0: the axis is not gauged).
  const Vec3& gauge_length() const { return gauge_length_; }
  // The boundary area of face f (0..5 = x-, x+, y-, y+, z-, z+) carried by its particles: the
  // loaded area under a platen on that face.
  Real face_area(int f) const { return area_[f]; }
  std::size_t interior_particles() const { return interior_.size(); }
  // summary.json's "gauges": face_gauge_length_m [3], face_area_m2 [6], interior_particles.
  nlohmann::ordered_json summary() const;

 private:
  const BoundaryFaces* faces_;
  Real area_[6] = {0, 0, 0, 0, 0, 0};
  Vec3 gauge_length_ = Vec3::Zero();
  std::vector<Index> interior_;
  Vec3 centre0_ = Vec3::Zero();  // mean initial position of the interior set
  Eigen::Matrix3d moment_inverse_ =
      Eigen::Matrix3d::Zero();  // (sum X X^T)^-1 of the centred positions
};

}  // namespace rcdem::io
