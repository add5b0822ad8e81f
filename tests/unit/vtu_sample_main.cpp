// vtu_sample OUTDIR: writes a small grid holding every cell kind and array type rcdem emits, in
// both encodings, so tests/regression/check_vtu_sample.sh can read it back with an independent
// reader (meshio). Values are chosen to expose lossy formatting (0.1, 1/3, -0.0, 1e-300, > 2^32).
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "rcdem/core/error.hpp"
#include "rcdem/io/vtu_writer.hpp"

namespace {

rcdem::io::UnstructuredGrid sample_grid() {
  using rcdem::Vec3;
  rcdem::io::UnstructuredGrid grid;
  grid.points = {Vec3(0.0, 0.0, 0.0), Vec3(0.1, 0.0, 0.0), Vec3(0.1, 1.0 / 3.0, 0.0),
                 Vec3(-0.0, 1.0 / 3.0, 1e-300)};
  grid.add_vertex_cells();
  grid.add_polygon(std::array<std::int64_t, 3>{0, 1, 2});
  grid.add_polygon(std::array<std::int64_t, 4>{0, 1, 2, 3});
  grid.add_line(1, 3);

  grid.add_point_data("radius", std::vector<double>{0.004, 0.0045, 0.005, 1.0 / 3.0});
  grid.add_point_data("kind", std::vector<std::int32_t>{0, 1, -1, 2147483647});
  grid.add_point_data("displacement",
                      std::vector<Vec3>{Vec3(1e-6, 0.0, -2e-6), Vec3(0.0, 0.0, 0.0),
                                        Vec3(0.1, 0.2, 0.3), Vec3(-1.5, 2.5, 1e300)});
  grid.add_point_data("id", std::vector<std::int64_t>{0, 1, 5000000000LL, -7});
  grid.add_cell_data("area", std::vector<double>{0, 0, 0, 0, 0.0166666666666667, 1.0 / 30.0, 0});
  grid.add_cell_data("family", std::vector<std::uint8_t>{0, 0, 0, 0, 1, 1, 255});
  return grid;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    fmt::print(stderr, "usage: vtu_sample OUTDIR\n");
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    const rcdem::io::UnstructuredGrid grid = sample_grid();
    rcdem::io::write_vtu(dir / "sample_ascii.vtu", grid, rcdem::io::VtuEncoding::Ascii);
    rcdem::io::write_vtu(dir / "sample_binary.vtu", grid, rcdem::io::VtuEncoding::Binary);
    rcdem::io::write_pvd(dir / "sample.pvd",
                         {{0.0, "sample_ascii.vtu"}, {0.5, "sample_binary.vtu"}});
  } catch (const rcdem::Error& e) {
    fmt::print(stderr, "vtu_sample: {}\n", e.what());
    return 1;
  }
  return 0;
}
