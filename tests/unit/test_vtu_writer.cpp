#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "rcdem/core/error.hpp"
#include "rcdem/io/vtu_writer.hpp"

namespace rcdem::io {
namespace {

std::string base64_of(std::string_view text) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
  return base64_encode(std::span(bytes, text.size()));
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

// A fresh directory per test, so parallel ctest runs never share files.
class VtuWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("rcdem_vtu_") + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

UnstructuredGrid small_grid() {
  UnstructuredGrid grid;
  grid.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0.1)};
  grid.add_vertex_cells();
  grid.add_polygon(std::array<std::int64_t, 3>{0, 1, 2});
  grid.add_polygon(std::array<std::int64_t, 4>{0, 1, 2, 3});
  grid.add_line(0, 2);
  grid.add_point_data("radius", std::vector<double>{0.1, 0.2, 1.0 / 3.0, 4e-5});
  grid.add_point_data("kind", std::vector<std::int32_t>{0, 1, 2, 3});
  grid.add_point_data("displacement", std::vector<Vec3>(4, Vec3(1e-6, -2e-6, 0.3)));
  grid.add_cell_data("area", std::vector<double>{0, 0, 0, 0, 0.5, 1.0, 0});
  grid.add_cell_data("family", std::vector<std::uint8_t>{0, 0, 0, 0, 1, 1, 2});
  grid.add_cell_data("id", std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6});
  return grid;
}

TEST(Base64, MatchesRfc4648TestVectors) {
  EXPECT_EQ(base64_of(""), "");
  EXPECT_EQ(base64_of("f"), "Zg==");
  EXPECT_EQ(base64_of("fo"), "Zm8=");
  EXPECT_EQ(base64_of("foo"), "Zm9v");
  EXPECT_EQ(base64_of("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_of("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_of("foobar"), "Zm9vYmFy");
}

TEST(Base64, UsesTheHighAlphabetCharacters) {
  const std::array<std::uint8_t, 3> bytes{0xfb, 0xff, 0xbf};
  EXPECT_EQ(base64_encode(bytes), "+/+/");
}

TEST_F(VtuWriterTest, MismatchedPointArrayLengthThrowsNamingTheArray) {
  UnstructuredGrid grid = small_grid();
  grid.add_point_data("too_short", std::vector<double>{1.0, 2.0});
  try {
    write_vtu(dir_ / "bad.vtu", grid, VtuEncoding::Ascii);
    FAIL() << "expected rcdem::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("too_short"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.vtu"));
}

TEST_F(VtuWriterTest, MismatchedCellArrayLengthThrows) {
  UnstructuredGrid grid = small_grid();
  grid.add_cell_data("per_point_by_mistake", std::vector<double>(grid.num_points(), 0.0));
  EXPECT_THROW(write_vtu(dir_ / "bad.vtu", grid, VtuEncoding::Binary), Error);
}

TEST_F(VtuWriterTest, InconsistentCellsThrow) {
  UnstructuredGrid missing_type = small_grid();
  missing_type.types.pop_back();
  EXPECT_THROW(write_vtu(dir_ / "bad.vtu", missing_type, VtuEncoding::Ascii), Error);

  UnstructuredGrid bad_point = small_grid();
  bad_point.add_line(0, 4);
  bad_point.cell_data.clear();
  EXPECT_THROW(write_vtu(dir_ / "bad.vtu", bad_point, VtuEncoding::Ascii), Error);

  UnstructuredGrid duplicate = small_grid();
  duplicate.add_point_data("radius", std::vector<double>(4, 1.0));
  EXPECT_THROW(write_vtu(dir_ / "bad.vtu", duplicate, VtuEncoding::Ascii), Error);

  UnstructuredGrid degenerate;
  EXPECT_THROW(degenerate.add_polygon(std::array<std::int64_t, 2>{0, 1}), Error);
}

TEST_F(VtuWriterTest, SameGridGivesByteIdenticalFiles) {
  const UnstructuredGrid grid = small_grid();
  for (const VtuEncoding encoding : {VtuEncoding::Ascii, VtuEncoding::Binary}) {
    write_vtu(dir_ / "a.vtu", grid, encoding);
    write_vtu(dir_ / "b.vtu", grid, encoding);
    const std::string a = read_file(dir_ / "a.vtu");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, read_file(dir_ / "b.vtu"));
  }
}

TEST_F(VtuWriterTest, AsciiHeaderCountsAndFullPrecision) {
  write_vtu(dir_ / "grid.vtu", small_grid(), VtuEncoding::Ascii);
  const std::string text = read_file(dir_ / "grid.vtu");
  EXPECT_NE(text.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(text.find("NumberOfPoints=\"4\""), std::string::npos);
  EXPECT_NE(text.find("NumberOfCells=\"7\""), std::string::npos);
  EXPECT_NE(text.find("0.33333333333333331"), std::string::npos);  // 17 significant digits
  EXPECT_NE(text.find("Name=\"displacement\" NumberOfComponents=\"3\""), std::string::npos);
}

TEST_F(VtuWriterTest, BinaryBlockStartsWithUInt64ByteCount) {
  UnstructuredGrid grid;
  grid.points = {Vec3(1, 2, 3)};
  grid.add_vertex_cells();
  write_vtu(dir_ / "one.vtu", grid, VtuEncoding::Binary);
  const std::string text = read_file(dir_ / "one.vtu");
  // types: 8-byte count (1) then the single byte 1 -> base64 of 01 00 00 00 00 00 00 00 01.
  EXPECT_NE(text.find("AQAAAAAAAAAB"), std::string::npos) << text;
}

TEST_F(VtuWriterTest, NamesAreXmlEscaped) {
  UnstructuredGrid grid = small_grid();
  grid.add_point_data("a<b&\"c\"", std::vector<double>(4, 0.0));
  write_vtu(dir_ / "grid.vtu", grid, VtuEncoding::Ascii);
  EXPECT_NE(read_file(dir_ / "grid.vtu").find("Name=\"a&lt;b&amp;&quot;c&quot;\""),
            std::string::npos);
}

TEST_F(VtuWriterTest, PvdListsEntriesInOrder) {
  write_pvd(dir_ / "series.pvd", {{0.0, "step_0.vtu"}, {0.25, "step_1.vtu"}});
  const std::string text = read_file(dir_ / "series.pvd");
  EXPECT_NE(text.find("type=\"Collection\""), std::string::npos);
  const auto first = text.find("timestep=\"0\" group=\"\" part=\"0\" file=\"step_0.vtu\"");
  const auto second = text.find("timestep=\"0.25\" group=\"\" part=\"0\" file=\"step_1.vtu\"");
  ASSERT_NE(first, std::string::npos);
  ASSERT_NE(second, std::string::npos);
  EXPECT_LT(first, second);
}

}  // namespace
}  // namespace rcdem::io
