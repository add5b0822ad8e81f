#pragma once
// A uniform grid of cells over a box, built by counting sort, for neighbour search among points.
// Candidates come in a fixed order, so every loop over them is deterministic.
#include <algorithm>
#include <cmath>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

class CellGrid {
 public:
  void build(const std::vector<Vec3>& points, const Vec3& lo, const Vec3& hi, Real cell_size) {
    lo_ = lo;
    for (int a = 0; a < 3; ++a)
      n_[a] = std::max(1, static_cast<int>(std::floor((hi[a] - lo[a]) / cell_size)));
    for (int a = 0; a < 3; ++a) h_[a] = (hi[a] - lo[a]) / n_[a];
    const std::size_t cells = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
    start_.assign(cells + 1, 0);
    cell_of_.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      cell_of_[i] = cell_index(points[i]);
      ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    items_.resize(points.size());
    std::vector<Index> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      items_[fill[cell_of_[i]]++] = static_cast<Index>(i);
  }

  // Calls f(j) for every point in the 27 cells around p.
  template <typename F>
  void for_each_near(const Vec3& p, F&& f) const {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = coord(p, a);
    for (int i = std::max(0, c[0] - 1); i <= std::min(n_[0] - 1, c[0] + 1); ++i)
      for (int j = std::max(0, c[1] - 1); j <= std::min(n_[1] - 1, c[1] + 1); ++j)
        for (int k = std::max(0, c[2] - 1); k <= std::min(n_[2] - 1, c[2] + 1); ++k) {
          const std::size_t cell = (static_cast<std::size_t>(k) * n_[1] + j) * n_[0] + i;
          for (Index m = start_[cell]; m < start_[cell + 1]; ++m) f(items_[m]);
        }
  }

 private:
  int coord(const Vec3& p, int a) const {
    const int c = static_cast<int>(std::floor((p[a] - lo_[a]) / h_[a]));
    return std::clamp(c, 0, n_[a] - 1);
  }
  std::size_t cell_index(const Vec3& p) const {
    return (static_cast<std::size_t>(coord(p, 2)) * n_[1] + coord(p, 1)) * n_[0] + coord(p, 0);
  }

  Vec3 lo_ = Vec3::Zero();
  int n_[3] = {1, 1, 1};
  Real h_[3] = {1, 1, 1};
  std::vector<Index> start_, items_;
  std::vector<std::size_t> cell_of_;
};

}  // namespace rcdem
