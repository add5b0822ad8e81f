#include "rcdem/packing/generator.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/error.hpp"
#include "rcdem/core/parallel.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/rng.hpp"
#include "rcdem/packing/bar_exclusion.hpp"
#include "rcdem/packing/cell_grid.hpp"
#include "rcdem/packing/grading.hpp"

namespace rcdem {

namespace {

Real sphere_volume(Real r) { return 4.0 / 3.0 * kPi * r * r * r; }

// Draws diameters whose spheres fill `target` as closely as one sphere allows. The draws are
// stratified: for the expected count N, one diameter from each of the N equal-probability bins of
// the grading, in random order. The grading is then honoured at any specimen size, and the count
// varies little from seed to seed (i.i.d. draws would scatter it by CV(d^3)/sqrt(N), 2% for a
// small cube). Past the N stratified draws, or if they overshoot, the sum is completed or trimmed
// so that the last sphere kept brings it closest to the target.
std::vector<Real> draw_radii(const DiameterDistribution& dist, Real target, Rng& rng) {
  const Real mean = dist.mean_volume();
  if (!(mean > 0.0) || !std::isfinite(mean))
    fail("the diameter distribution in [{}, {}] m has no finite mean volume", dist.d_min,
         dist.d_max);
  const auto expected = static_cast<std::size_t>(std::llround(target / mean));
  std::vector<Real> radii(expected);
  for (std::size_t k = 0; k < expected; ++k)
    radii[k] =
        0.5 * dist.quantile((static_cast<Real>(k) + rng.uniform()) / static_cast<Real>(expected));
  for (std::size_t k = expected; k > 1; --k) {  // Fisher-Yates with our own generator
    const auto j = static_cast<std::size_t>(rng.uniform() * static_cast<Real>(k));
    std::swap(radii[k - 1], radii[j]);
  }
  std::vector<Real> kept;
  Real sum = 0.0;
  for (Real r : radii) {
    const Real v = sphere_volume(r);
    if (sum + v - target > target - sum) break;
    kept.push_back(r);
    sum += v;
  }
  while (sum < target) {
    const Real r = 0.5 * dist.sample(rng);
    const Real v = sphere_volume(r);
    if (sum + v - target > target - sum) break;
    kept.push_back(r);
    sum += v;
  }
  return kept;
}

// Keeps p at least `margin` from every face and outside the notch slot by `margin`.
Vec3 clamp_inside(Vec3 p, const SpecimenGeometry& g, Real margin) {
  for (int a = 0; a < 3; ++a) p[a] = std::clamp(p[a], g.lo[a] + margin, g.hi[a] - margin);
  if (g.notch.present()) {
    const Real half = 0.5 * g.notch.width + margin;
    const Real top = g.lo.z() + g.notch.depth + margin;
    const Real dx = p.x() - g.notch.x_center;
    if (std::abs(dx) < half && p.z() < top) {
      // Leave the slot by the shorter way: sideways or upwards.
      const Real side = half - std::abs(dx);
      const Real up = top - p.z();
      if (side <= up)
        p.x() = g.notch.x_center + (dx < 0.0 ? -half : half);
      else
        p.z() = top;
    }
  }
  return p;
}

// Push of the boundary on a particle that overlaps it, as a rigid wall would.
Vec3 boundary_push(const Vec3& p, Real r, const SpecimenGeometry& g) {
  Vec3 push = Vec3::Zero();
  for (int a = 0; a < 3; ++a) {
    const Real below = r - (p[a] - g.lo[a]);
    const Real above = r - (g.hi[a] - p[a]);
    if (below > 0.0) push[a] += below;
    if (above > 0.0) push[a] -= above;
  }
  if (g.notch.present()) {
    const Real half = 0.5 * g.notch.width;
    const Real top = g.lo.z() + g.notch.depth;
    const Real dx = p.x() - g.notch.x_center;
    if (p.z() < top) {
      const Real o = r - (std::abs(dx) - half);
      if (o > 0.0) push.x() += dx < 0.0 ? -o : o;
    } else if (std::abs(dx) < half) {
      const Real o = r - (p.z() - top);
      if (o > 0.0) push.z() += o;
    }
  }
  return push;
}

// The generator fills the solid volume to within one sphere: a target porosity finer than that
// cannot be met, and is refused rather than silently missed.
void check_porosity_met(const GenerationSettings& s, Real volume, Real agg_volume,
                        const std::vector<Real>& mortar_radii) {
  Real solid = agg_volume;
  for (Real r : mortar_radii) solid += sphere_volume(r);
  const Real reached = 1.0 - solid / volume;
  if (std::abs(reached - s.porosity) <= 0.1 * s.porosity) return;
  const Real one = sphere_volume(0.5 * s.mortar_d_max) / volume;
  fail(
      "key 'generation.porosity' = {} cannot be met: the spheres drawn leave a porosity of {:.3g} "
      "(the generator fills the volume to within one sphere, and the largest mortar sphere is "
      "{:.3g} of it); expected a porosity of at least {:.3g}",
      s.porosity, reached, one, 10.0 * one);
}

}  // namespace

Particles generate_packing(const GenerationSettings& s, const SpecimenGeometry& g,
                           PackingReport* report, const std::vector<BarSettings>& bar_settings) {
  Rng rng(s.seed);
  const std::vector<BarAxis> bars = bar_axes(bar_settings);
  Real bar_volume = 0.0;
  for (const auto& b : bar_settings)
    bar_volume += 0.25 * kPi * b.diameter * b.diameter * b.length();
  const Real volume = g.volume() - bar_volume;  // the concrete's volume

  const DiameterDistribution aggregate{s.aggregate_grading, s.aggregate_d_min, s.aggregate_d_max,
                                       s.fuller_exponent};
  const DiameterDistribution mortar{Grading::Uniform, s.mortar_d_min, s.mortar_d_max, 0.5};

  const Real aggregate_target = s.aggregate_content / s.aggregate_density * volume;
  std::vector<Real> agg_radii = draw_radii(aggregate, aggregate_target, rng);
  Real agg_volume = 0.0;
  for (Real r : agg_radii) agg_volume += sphere_volume(r);
  const Real solid_target = (1.0 - s.porosity) * volume;
  if (agg_volume >= solid_target)
    fail(
        "the aggregate alone ({:.4g} m^3) exceeds the solid volume allowed by porosity {} "
        "({:.4g} m^3)",
        agg_volume, s.porosity, solid_target);
  std::vector<Real> mortar_radii = draw_radii(mortar, solid_target - agg_volume, rng);
  check_porosity_met(s, volume, agg_volume, mortar_radii);

  Particles particles;
  const std::size_t n = agg_radii.size() + mortar_radii.size();
  if (n == 0) fail("the specimen holds no particle: check its size and the porosity");
  particles.position.reserve(n);
  const Real f = s.min_distance_factor;
  auto place = [&](Real r, ParticleKind kind) {
    // Uniform in the region the centre may occupy; rejection keeps it out of the notch.
    for (int attempt = 0; attempt < 1000; ++attempt) {
      Vec3 p;
      for (int a = 0; a < 3; ++a) p[a] = rng.uniform(g.lo[a] + f * r, g.hi[a] - f * r);
      if (g.distance_to_boundary(p) >= f * r && !g.in_notch(p) && !near_bar(p, f * r, bars)) {
        particles.add(p, r, kind);
        return;
      }
    }
    fail("could not place a particle of radius {} m inside the specimen", r);
  };
  for (Real r : agg_radii) place(r, ParticleKind::Aggregate);
  for (Real r : mortar_radii) place(r, ParticleKind::Mortar);

  // Relaxation in the manner of PFC's radius expansion and cycling: damped dynamics on the sum of
  // squared overlaps with the neighbours and the faces. Each iteration's move is a step along the
  // overlap push plus a fraction of the previous move (heavy-ball momentum: long-wavelength density
  // fluctuations of the random start then relax in a few hundred iterations, where plain gradient
  // steps would need thousands). Jacobi updates: every move is computed from the same positions,
  // so the result does not depend on the thread count.
  const Real r_max = *std::max_element(particles.radius.begin(), particles.radius.end());
  const Index count = particles.size();
  std::vector<Vec3> move(static_cast<std::size_t>(count), Vec3::Zero());
  CellGrid grid;
  Progress progress("relaxation", count < 20000);
  constexpr Real step = 0.15;
  constexpr Real momentum = 0.8;
  for (int it = 0; it < s.relaxation_iterations; ++it) {
    grid.build(particles.position, g.lo, g.hi, 2.0 * r_max);
    const Vec3* x = particles.position.data();
    const Real* rad = particles.radius.data();
    parallel_for(count, [&](Index i) {
      Vec3 m = boundary_push(x[i], rad[i], g) + bar_push(x[i], rad[i], bars);
      grid.for_each_near(x[i], [&](Index j) {
        if (j == i) return;
        const Vec3 d = x[i] - x[j];
        const Real dist = d.norm();
        const Real overlap = rad[i] + rad[j] - dist;
        if (overlap > 0.0 && dist > 0.0) m += (0.5 * overlap / dist) * d;
      });
      // Capped so that no particle jumps past its neighbours in the first, crowded iterations.
      const Vec3 v = momentum * move[i] + step * m;
      const Real len = v.norm();
      const Real cap = 0.2 * rad[i];
      move[i] = len > cap ? Vec3(v * (cap / len)) : v;
    });
    parallel_for(count, [&](Index i) {
      particles.position[i] =
          clamp_inside(keep_off_bars(x[i] + move[i], f * rad[i], bars), g, f * rad[i]);
    });
    progress.update(static_cast<double>(it + 1) / s.relaxation_iterations);
  }
  progress.done();

  if (report) {
    PackingReport& rep = *report;
    rep.aggregate_volume = agg_volume;
    rep.sphere_volume = 0.0;
    for (Real r : particles.radius) rep.sphere_volume += sphere_volume(r);
    rep.porosity = 1.0 - rep.sphere_volume / volume;  // of the concrete
    grid.build(particles.position, g.lo, g.hi, 2.0 * r_max);
    Real min_pair = std::numeric_limits<Real>::infinity();
    Real min_face = std::numeric_limits<Real>::infinity();
    Real min_bar = std::numeric_limits<Real>::infinity();
    for (Index i = 0; i < count; ++i) {
      const Vec3& xi = particles.position[i];
      min_face = std::min(min_face, g.distance_to_boundary(xi) / particles.radius[i]);
      for (const auto& bar : bars)
        min_bar =
            std::min(min_bar, ((xi - bar.closest(xi)).norm() - bar.radius) / particles.radius[i]);
      grid.for_each_near(xi, [&](Index j) {
        if (j <= i) return;
        const Real d = (xi - particles.position[j]).norm();
        min_pair = std::min(min_pair, d / std::min(particles.radius[i], particles.radius[j]));
      });
    }
    rep.min_distance_ratio = min_pair;
    rep.min_face_ratio = min_face;
    rep.min_bar_ratio = min_bar;
  }
  return particles;
}

}  // namespace rcdem
