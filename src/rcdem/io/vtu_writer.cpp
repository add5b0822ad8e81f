#include "rcdem/io/vtu_writer.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <iterator>
#include <set>
#include <string_view>
#include <type_traits>

#include "rcdem/core/error.hpp"
#include "rcdem/io/atomic_file.hpp"

namespace rcdem::io {

// The binary encoding copies the in-memory bytes and declares byte_order="LittleEndian".
static_assert(std::endian::native == std::endian::little,
              "VTU binary output assumes little-endian");

namespace {

void base64_append(std::string& out, std::span<const std::uint8_t> in) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  out.reserve(out.size() + (in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= in.size(); i += 3) {
    const std::uint32_t v =
        (std::uint32_t{in[i]} << 16) | (std::uint32_t{in[i + 1]} << 8) | std::uint32_t{in[i + 2]};
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  const std::size_t rest = in.size() - i;
  if (rest == 0) return;
  std::uint32_t v = std::uint32_t{in[i]} << 16;
  if (rest == 2) v |= std::uint32_t{in[i + 1]} << 8;
  out += kAlphabet[(v >> 18) & 63];
  out += kAlphabet[(v >> 12) & 63];
  out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
  out += '=';
}

// Array names come from user configuration, so they may hold XML-special characters.
std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

template <typename T>
constexpr std::string_view vtk_type_name() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
}

template <typename T>
void append_data_array(std::string& out, std::string_view name, int components,
                       std::span<const T> values, VtuEncoding encoding) {
  const std::string_view format = encoding == VtuEncoding::Binary ? "binary" : "ascii";
  fmt::format_to(std::back_inserter(out), "        <DataArray type=\"{}\" Name=\"{}\"",
                 vtk_type_name<T>(), xml_escape(name));
  // Left out for scalars, as VTK itself does, so readers such as meshio give flat arrays.
  if (components > 1)
    fmt::format_to(std::back_inserter(out), " NumberOfComponents=\"{}\"", components);
  fmt::format_to(std::back_inserter(out), " format=\"{}\">\n", format);
  if (encoding == VtuEncoding::Binary) {
    // One uncompressed block: a UInt64 byte count, then the raw values, base64-encoded together.
    const std::uint64_t byte_count = values.size() * sizeof(T);
    std::vector<std::uint8_t> block(sizeof(byte_count) + byte_count);
    std::memcpy(block.data(), &byte_count, sizeof(byte_count));
    if (byte_count > 0) std::memcpy(block.data() + sizeof(byte_count), values.data(), byte_count);
    out += "          ";
    base64_append(out, block);
    out += '\n';
  } else {
    // Whole tuples per line keep vectors readable; scalars are wrapped to keep lines short.
    const std::size_t per_line = components > 1 ? static_cast<std::size_t>(components) : 8;
    for (std::size_t i = 0; i < values.size(); ++i) {
      out += i % per_line == 0 ? "          " : " ";
      if constexpr (std::is_same_v<T, double>) {
        fmt::format_to(std::back_inserter(out), "{:.17g}", values[i]);
      } else {
        fmt::format_to(std::back_inserter(out), "{}", static_cast<std::int64_t>(values[i]));
      }
      if (i % per_line == per_line - 1 || i + 1 == values.size()) out += '\n';
    }
  }
  out += "        </DataArray>\n";
}

std::size_t array_size(const VtuArray& array) {
  return std::visit([](const auto& v) { return v.size(); }, array.data);
}

void check_arrays(const std::filesystem::path& path, std::string_view kind,
                  const std::vector<VtuArray>& arrays, std::size_t count,
                  std::string_view count_name) {
  std::set<std::string_view> seen;
  for (const VtuArray& array : arrays) {
    if (array.name.empty()) fail("cannot write '{}': a {} array has no name", path.string(), kind);
    if (!seen.insert(array.name).second) {
      fail("cannot write '{}': {} array '{}' appears twice", path.string(), kind, array.name);
    }
    if (array.components < 1) {
      fail("cannot write '{}': {} array '{}' has {} components", path.string(), kind, array.name,
           array.components);
    }
    const std::size_t expected = static_cast<std::size_t>(array.components) * count;
    if (array_size(array) != expected) {
      fail("cannot write '{}': {} array '{}' has {} values, expected {} ({} {} x {} components)",
           path.string(), kind, array.name, array_size(array), expected, count, count_name,
           array.components);
    }
  }
}

void check_cells(const std::filesystem::path& path, const UnstructuredGrid& grid) {
  if (grid.offsets.size() != grid.types.size()) {
    fail("cannot write '{}': {} cell offsets but {} cell types", path.string(), grid.offsets.size(),
         grid.types.size());
  }
  std::int64_t begin = 0;
  for (std::size_t c = 0; c < grid.offsets.size(); ++c) {
    const std::int64_t end = grid.offsets[c];
    if (end < begin || end > static_cast<std::int64_t>(grid.connectivity.size())) {
      fail("cannot write '{}': cell {} has offset {} outside [{}, {}]", path.string(), c, end,
           begin, grid.connectivity.size());
    }
    const std::int64_t size = end - begin;
    const std::uint8_t type = grid.types[c];
    if ((type == kVtkVertex && size != 1) || (type == kVtkLine && size != 2) ||
        (type == kVtkPolygon && size < 3)) {
      fail("cannot write '{}': cell {} of VTK type {} has {} points", path.string(), c, int{type},
           size);
    }
    begin = end;
  }
  if (begin != static_cast<std::int64_t>(grid.connectivity.size())) {
    fail("cannot write '{}': cells use {} connectivity entries but there are {}", path.string(),
         begin, grid.connectivity.size());
  }
  const auto num_points = static_cast<std::int64_t>(grid.points.size());
  for (const std::int64_t id : grid.connectivity) {
    if (id < 0 || id >= num_points) {
      fail("cannot write '{}': cell connectivity refers to point {} but there are {} points",
           path.string(), id, num_points);
    }
  }
}

void append_section(std::string& out, std::string_view tag, const std::vector<VtuArray>& arrays,
                    VtuEncoding encoding) {
  if (arrays.empty()) return;
  fmt::format_to(std::back_inserter(out), "      <{}>\n", tag);
  for (const VtuArray& array : arrays) {
    std::visit(
        [&](const auto& values) {
          append_data_array(out, array.name, array.components, std::span(values), encoding);
        },
        array.data);
  }
  fmt::format_to(std::back_inserter(out), "      </{}>\n", tag);
}

std::vector<double> flatten(const std::vector<Vec3>& vectors) {
  std::vector<double> flat;
  flat.reserve(3 * vectors.size());
  for (const Vec3& v : vectors) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  return flat;
}

}  // namespace

std::string base64_encode(std::span<const std::uint8_t> bytes) {
  std::string out;
  base64_append(out, bytes);
  return out;
}

void UnstructuredGrid::add_vertex_cells() {
  const auto n = static_cast<std::int64_t>(points.size());
  for (std::int64_t i = 0; i < n; ++i) {
    connectivity.push_back(i);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(kVtkVertex);
  }
}

void UnstructuredGrid::add_polygon(std::span<const std::int64_t> point_ids) {
  if (point_ids.size() < 3) fail("a VTK polygon needs at least 3 points, got {}", point_ids.size());
  connectivity.insert(connectivity.end(), point_ids.begin(), point_ids.end());
  offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  types.push_back(kVtkPolygon);
}

void UnstructuredGrid::add_line(std::int64_t a, std::int64_t b) {
  connectivity.insert(connectivity.end(), {a, b});
  offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  types.push_back(kVtkLine);
}

void UnstructuredGrid::add_point_data(std::string name, std::vector<double> values) {
  point_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_point_data(std::string name, const std::vector<Vec3>& values) {
  point_data.push_back({std::move(name), 3, flatten(values)});
}
void UnstructuredGrid::add_point_data(std::string name, std::vector<std::int32_t> values) {
  point_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_point_data(std::string name, std::vector<std::int64_t> values) {
  point_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_point_data(std::string name, std::vector<std::uint8_t> values) {
  point_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_cell_data(std::string name, std::vector<double> values) {
  cell_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_cell_data(std::string name, const std::vector<Vec3>& values) {
  cell_data.push_back({std::move(name), 3, flatten(values)});
}
void UnstructuredGrid::add_cell_data(std::string name, std::vector<std::int32_t> values) {
  cell_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_cell_data(std::string name, std::vector<std::int64_t> values) {
  cell_data.push_back({std::move(name), 1, std::move(values)});
}
void UnstructuredGrid::add_cell_data(std::string name, std::vector<std::uint8_t> values) {
  cell_data.push_back({std::move(name), 1, std::move(values)});
}

void write_vtu(const std::filesystem::path& path, const UnstructuredGrid& grid,
               VtuEncoding encoding) {
  check_cells(path, grid);
  check_arrays(path, "point-data", grid.point_data, grid.num_points(), "points");
  check_arrays(path, "cell-data", grid.cell_data, grid.num_cells(), "cells");

  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out +=
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  fmt::format_to(std::back_inserter(out),
                 "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", grid.num_points(),
                 grid.num_cells());

  out += "      <Points>\n";
  const std::vector<double> coordinates = flatten(grid.points);
  append_data_array(out, "Points", 3, std::span(coordinates), encoding);
  out += "      </Points>\n";

  out += "      <Cells>\n";
  append_data_array(out, "connectivity", 1, std::span(grid.connectivity), encoding);
  append_data_array(out, "offsets", 1, std::span(grid.offsets), encoding);
  append_data_array(out, "types", 1, std::span(grid.types), encoding);
  out += "      </Cells>\n";

  append_section(out, "PointData", grid.point_data, encoding);
  append_section(out, "CellData", grid.cell_data, encoding);

  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
  write_file_atomically(path, out);
}

void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& entries) {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <Collection>\n";
  for (const auto& [time, file] : entries) {
    if (!std::isfinite(time)) fail("cannot write '{}': time {} of '{}'", path.string(), time, file);
    if (file.empty())
      fail("cannot write '{}': an entry at time {} has no file", path.string(), time);
    fmt::format_to(std::back_inserter(out),
                   "    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time,
                   xml_escape(file));
  }
  out += "  </Collection>\n";
  out += "</VTKFile>\n";
  write_file_atomically(path, out);
}

}  // namespace rcdem::io
