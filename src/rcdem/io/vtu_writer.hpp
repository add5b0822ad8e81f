#pragma once
// A small VTK XML (.vtu/.pvd) writer of our own: libvtk on Debian pulls in a JDK, GDAL and MySQL,
// and we only ever need one unstructured-grid piece with inline data.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem::io {

// Binary is inline base64 (header_type="UInt64"): exact, several times faster to write, about 40%
// smaller than ascii, and still one self-contained XML file. Ascii is for diffing and debugging.
enum class VtuEncoding { Ascii, Binary };

struct VtuArray {
  using Data = std::variant<std::vector<double>, std::vector<std::int32_t>,
                            std::vector<std::int64_t>, std::vector<std::uint8_t>>;
  std::string name;
  int components = 1;
  Data data;  // tuples stored one after another: size == components * number of points or cells
};

// VTK cell types used by rcdem.
inline constexpr std::uint8_t kVtkVertex = 1;
inline constexpr std::uint8_t kVtkLine = 3;
inline constexpr std::uint8_t kVtkPolygon = 7;

struct UnstructuredGrid {
  std::vector<Vec3> points;
  std::vector<std::int64_t> connectivity;  // point ids of all cells, concatenated
  std::vector<std::int64_t> offsets;  // VTK convention: end offset of each cell in connectivity
  std::vector<std::uint8_t> types;    // kVtkVertex, kVtkLine, kVtkPolygon
  std::vector<VtuArray> point_data, cell_data;

  std::size_t num_points() const { return points.size(); }
  std::size_t num_cells() const { return types.size(); }

  // Particles are drawn as points: one vertex cell for each point present now.
  void add_vertex_cells();
  void add_polygon(std::span<const std::int64_t> point_ids);  // at least 3 ids
  void add_line(std::int64_t a, std::int64_t b);

  // Lengths are checked by write_vtu, not here, so fields may be added before the cells.
  void add_point_data(std::string name, std::vector<double> values);
  void add_point_data(std::string name, const std::vector<Vec3>& values);  // 3 components
  void add_point_data(std::string name, std::vector<std::int32_t> values);
  void add_point_data(std::string name, std::vector<std::int64_t> values);
  void add_point_data(std::string name, std::vector<std::uint8_t> values);
  void add_cell_data(std::string name, std::vector<double> values);
  void add_cell_data(std::string name, const std::vector<Vec3>& values);  // 3 components
  void add_cell_data(std::string name, std::vector<std::int32_t> values);
  void add_cell_data(std::string name, std::vector<std::int64_t> values);
  void add_cell_data(std::string name, std::vector<std::uint8_t> values);
};

// Throws rcdem::Error if the grid is inconsistent (array lengths, offsets, point ids, names).
// The same grid always gives the same bytes; the file is replaced atomically.
void write_vtu(const std::filesystem::path& path, const UnstructuredGrid& grid,
               VtuEncoding encoding);

// A ParaView .pvd collection (time series): entries (time, file name relative to the .pvd).
void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& entries);

// RFC 4648 base64 with '=' padding; exposed for testing.
std::string base64_encode(std::span<const std::uint8_t> bytes);

}  // namespace rcdem::io
