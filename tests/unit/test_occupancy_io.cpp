// The occupancy files (env/occupancy_io.hpp): MovingAI .map, voxel .3dmap, NumPy .npy and the
// scenario files, good and bad, and the four MovingAI maps of the shared benchmark folder with
// their scenarios (HPCPLAN_MOVINGAI_DIR; a missing folder fails, it does not skip).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/occupancy_io.hpp"

#ifndef HPCPLAN_MOVINGAI_DIR
#define HPCPLAN_MOVINGAI_DIR "/work/shared/benchmarks/movingai"
#endif

namespace hpcplan::env {
namespace {

namespace fs = std::filesystem;

// Passes when `f` throws an InputError whose one-line message holds every word; any other
// exception escapes and fails the test.
::testing::AssertionResult Fails(const std::function<void()>& f,
                                 std::initializer_list<std::string_view> words) {
  std::string what;
  try {
    f();
    return ::testing::AssertionFailure() << "no InputError";
  } catch (const InputError& e) {
    what = e.what();
  }
  if (what.find('\n') != std::string::npos || what.find('\r') != std::string::npos)
    return ::testing::AssertionFailure() << "not one line: " << what;
  for (std::string_view w : words)
    if (what.find(w) == std::string::npos)
      return ::testing::AssertionFailure() << "'" << w << "' not in: " << what;
  return ::testing::AssertionSuccess() << what;
}

bool free_at(const OccupancyGrid& g, std::initializer_list<int> c) {
  return g.is_free(std::vector<int>(c));
}

// ---- .map -------------------------------------------------------------------------------

TEST(MovingAiMap, ReadsHeaderRowsAndEveryCharacter) {
  const std::string text =
      "type octile\nheight 3\nwidth 4\nmap\n"
      ".G@S\n"
      "OT.W\n"
      "....\n";
  const OccupancyGrid g = parse_movingai_map(text, "t.map");
  ASSERT_EQ(g.dims(), 2);
  EXPECT_EQ(g.size(0), 4);  // x: the column
  EXPECT_EQ(g.size(1), 3);  // y: the row
  EXPECT_EQ(g.format, "movingai");
  EXPECT_EQ(g.name, "t.map");
  // Ground: . G S; blocked: @ O T and, on ground terrain, W.
  EXPECT_TRUE(free_at(g, {0, 0}));
  EXPECT_TRUE(free_at(g, {1, 0}));
  EXPECT_FALSE(free_at(g, {2, 0}));
  EXPECT_TRUE(free_at(g, {3, 0}));
  EXPECT_FALSE(free_at(g, {0, 1}));
  EXPECT_FALSE(free_at(g, {1, 1}));
  EXPECT_TRUE(free_at(g, {2, 1}));
  EXPECT_FALSE(free_at(g, {3, 1}));
  EXPECT_EQ(g.free_cells(), 3u + 1u + 4u);
}

TEST(MovingAiMap, WaterIsAClassOfItsOwn) {
  const std::string text = "type octile\nheight 2\nwidth 3\nmap\nWW.\n@WG\n";
  const OccupancyGrid water = parse_movingai_map(text, "w.map", Terrain::water);
  EXPECT_TRUE(free_at(water, {0, 0}));
  EXPECT_TRUE(free_at(water, {1, 0}));
  EXPECT_FALSE(free_at(water, {2, 0}));  // ground, blocked from water
  EXPECT_FALSE(free_at(water, {0, 1}));  // out of bounds either way
  EXPECT_TRUE(free_at(water, {1, 1}));
  EXPECT_FALSE(free_at(water, {2, 1}));
  EXPECT_EQ(water.free_cells(), 3u);
  const OccupancyGrid ground = parse_movingai_map(text, "w.map");
  EXPECT_EQ(ground.free_cells(), 2u);
  EXPECT_TRUE(free_at(ground, {2, 0}));
  EXPECT_FALSE(free_at(ground, {0, 0}));
}

TEST(MovingAiMap, AcceptsCrlfTrailingBlankLinesSpacesAndAnyCase) {
  const std::string crlf = "type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.@.\r\n...\r\n\r\n\r\n";
  const OccupancyGrid a = parse_movingai_map(crlf, "crlf.map");
  const std::string lf = "TYPE octile\nWidth 3\nHEIGHT 2\nMap\n.@.  \n...\t\n\n   \n";
  const OccupancyGrid b = parse_movingai_map(lf, "lf.map");
  EXPECT_EQ(a.checksum(), b.checksum());
  EXPECT_EQ(a.free_cells(), 5u);
  // No final line end at all.
  EXPECT_EQ(parse_movingai_map("type octile\nheight 1\nwidth 2\nmap\n.@", "n.map").free_cells(),
            1u);
}

TEST(MovingAiMap, ErrorsNameTheFileAndLine) {
  const auto map = [](const std::string& text) {
    return [text] { parse_movingai_map(text, "bad.map"); };
  };
  const std::string head = "type octile\nheight 2\nwidth 3\nmap\n";
  EXPECT_TRUE(Fails(map(""), {"bad.map", "empty"}));
  EXPECT_TRUE(Fails(map("height 2\nwidth 3\nmap\n...\n...\n"), {"bad.map:1:", "type octile"}));
  EXPECT_TRUE(Fails(map("type octile\nheight 2\nwidth 3\n"), {"bad.map", "'map' line"}));
  EXPECT_TRUE(Fails(map("type octile\nheight 2\nmap\n...\n"), {"bad.map:3:", "width"}));
  EXPECT_TRUE(Fails(map("type octile\nheight x\nwidth 3\nmap\n"), {"bad.map:2:", "'x'", "whole"}));
  EXPECT_TRUE(Fails(map("type octile\nheight 2\nwidth 0\nmap\n"), {"bad.map:3:", "1..65535"}));
  EXPECT_TRUE(Fails(map("type octile\nheight 2\nheight 2\nmap\n"), {"bad.map:3:", "second"}));
  EXPECT_TRUE(Fails(map("type octile\nsize 2\nwidth 3\nmap\n"), {"bad.map:2:", "'size 2'"}));
  EXPECT_TRUE(Fails(map(head + "..\n...\n"), {"bad.map:5:", "row 0", "short"}));
  EXPECT_TRUE(Fails(map(head + "...\n....\n"), {"bad.map:6:", "row 1", "longer"}));
  EXPECT_TRUE(Fails(map(head + "...\n.x.\n"), {"bad.map:6:", "unknown character 'x'", "column 1"}));
  EXPECT_TRUE(Fails(map(head + "...\n.\x01.\n"), {"bad.map:6:", "'\\x01'"}));
  EXPECT_TRUE(Fails(map(head + "...    \n"), {"bad.map", "ends after 1 of the 2 rows"}));
  EXPECT_TRUE(Fails(map(head + "...\n...\n...\n"), {"bad.map:7:", "text after the 2 rows"}));
  // A claim the text cannot hold is refused before the grid (65535 x 65535 bits, 512 MiB)
  // is allocated.
  EXPECT_TRUE(Fails(map("type octile\nheight 65535\nwidth 65535\nmap\n...\n"),
                    {"bad.map:4:", "claims 65535 rows of 65535", "only 4 bytes"}));
}

TEST(MovingAiMap, CellOfTheTextForTheStartsTerrain) {
  const std::string text = "type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.W@\r\nT..\r\n";
  EXPECT_EQ(movingai_cell(text, 1, 0), 'W');
  EXPECT_EQ(movingai_cell(text, 0, 1), 'T');
  EXPECT_EQ(movingai_cell(text, 2, 1), '.');
  EXPECT_EQ(movingai_cell(text, 3, 0), std::nullopt);
  EXPECT_EQ(movingai_cell(text, 0, 2), std::nullopt);
  EXPECT_EQ(movingai_cell(text, -1, 0), std::nullopt);
  EXPECT_EQ(movingai_cell("not a map", 0, 0), std::nullopt);
  EXPECT_EQ(movingai_cell("type octile\nheight 2\nwidth 3\nmap\n.W@\n", 0, 1), std::nullopt);
}

// ---- .3dmap -----------------------------------------------------------------------------

TEST(VoxelMap, BlocksTheListedVoxels) {
  const OccupancyGrid g =
      parse_voxel_map("voxel 4 3 2\r\n0 0 0\r\n3 2 1\r\n1 2 0\r\n3 2 1\r\n\r\n", "v.3dmap");
  ASSERT_EQ(g.dims(), 3);
  EXPECT_EQ(g.shape(), (std::vector<int>{4, 3, 2}));
  EXPECT_EQ(g.format, "voxel");
  EXPECT_EQ(g.free_cells(), 24u - 3u);  // a voxel listed twice is blocked once
  EXPECT_FALSE(free_at(g, {0, 0, 0}));
  EXPECT_FALSE(free_at(g, {3, 2, 1}));
  EXPECT_FALSE(free_at(g, {1, 2, 0}));
  EXPECT_TRUE(free_at(g, {2, 1, 0}));
  EXPECT_TRUE(free_at(g, {1, 2, 1}));
  EXPECT_EQ(parse_voxel_map("VOXEL 1 1 1", "one.3dmap").free_cells(), 1u);
}

TEST(VoxelMap, ErrorsNameTheFileAndLine) {
  const auto voxel = [](const std::string& text) {
    return [text] { parse_voxel_map(text, "bad.3dmap"); };
  };
  EXPECT_TRUE(Fails(voxel(""), {"bad.3dmap", "empty"}));
  EXPECT_TRUE(Fails(voxel("voxels 2 2 2\n"), {"bad.3dmap:1:", "voxel W H D"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2\n"), {"bad.3dmap:1:", "voxel W H D"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 two 2\n"), {"bad.3dmap:1:", "'two'", "whole"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2 70000\n"), {"bad.3dmap:1:", "1..65535"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2 2\n0 0 0\n1 1\n"), {"bad.3dmap:3:", "'x y z'"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2 2\n0 0 0 0\n"), {"bad.3dmap:2:", "'x y z'"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2 2\n0 0 1.5\n"), {"bad.3dmap:2:", "'1.5'", "whole"}));
  EXPECT_TRUE(
      Fails(voxel("voxel 2 2 2\n\n0 2 0\n"), {"bad.3dmap:3:", "out of range", "(0, 2, 0)"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2 2\n-1 0 0\n"), {"bad.3dmap:2:", "out of range"}));
  EXPECT_TRUE(Fails(voxel("voxel 2 2 2\n0 0 99999999999999999999\n"), {"bad.3dmap:2:", "whole"}));
  // An absurd size is refused cheaply (2.8e14 voxels; 1 x 65535 x 65535 is 4.3e9 voxels but,
  // its rows padded to 64 bits, a grid of 32 GiB), and so is one past a caller's limit.
  EXPECT_TRUE(Fails(voxel("voxel 65535 65535 65535\n"), {"bad.3dmap:1:", "more than"}));
  EXPECT_TRUE(Fails(voxel("voxel 1 65535 65535\n"), {"bad.3dmap:1:", "34358689800 bytes"}));
  EXPECT_TRUE(Fails([] { parse_voxel_map("voxel 100 100 100\n", "small.3dmap", 159'999); },
                    {"small.3dmap:1:", "160000 bytes, more than the 159999"}));
  // Past the caller's limit, the grid's own refusal names the file too.
  EXPECT_TRUE(Fails([] { parse_voxel_map("voxel 65535 65535 65535\n", "huge.3dmap", ~0ull); },
                    {"huge.3dmap: ", "8 TiB"}));
  EXPECT_EQ(parse_voxel_map("voxel 100 100 100\n", "small.3dmap", 160'000).free_cells(),
            1'000'000u);
}

TEST(VoxelMap, AMillionLinesParseQuickly) {
  std::string text = "voxel 100 100 100\n";
  text.reserve(13'000'000);
  for (int z = 0; z < 100; ++z)
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 100; ++x)
        text += std::to_string(x) + ' ' + std::to_string(y) + ' ' + std::to_string(z) + '\n';
  const auto t0 = std::chrono::steady_clock::now();
  const OccupancyGrid g = parse_voxel_map(text, "big.3dmap");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(g.free_cells(), 0u);
  RecordProperty("parse_seconds", std::to_string(s));
}

// ---- .npy -------------------------------------------------------------------------------

// A .npy file by hand: the preamble of `major`.0, the dict padded to 64 bytes, the data.
std::string npy_file(const std::string& dict, const std::string& data, int major = 1) {
  const std::size_t preamble = major == 1 ? 10 : 12;
  std::string header = dict;
  while ((preamble + header.size() + 1) % 64) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += static_cast<char>(major);
  out += '\0';
  for (std::size_t i = 0; i < preamble - 8; ++i)
    out += static_cast<char>((header.size() >> (8 * i)) & 0xFF);
  return out + header + data;
}

std::string dict(const std::string& descr, bool fortran, const std::string& shape) {
  return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
         ", 'shape': " + shape + ", }";
}

TEST(Npy, COrderBoolAndUint8AllVersions) {
  // A (2, 3) array: rows y = 0, 1; the last axis is x.
  const std::string data("\x01\x00\x00\x00\x00\x07", 6);
  for (const char* descr : {"|b1", "|u1", "u1", "<u1", "bool"})
    for (int major : {1, 2, 3}) {
      const OccupancyGrid g =
          parse_npy(npy_file(dict(descr, false, "(2, 3)"), data, major), "a.npy");
      EXPECT_EQ(g.shape(), (std::vector<int>{3, 2})) << descr << " v" << major;
      EXPECT_FALSE(free_at(g, {0, 0}));
      EXPECT_TRUE(free_at(g, {1, 0}));
      EXPECT_FALSE(free_at(g, {2, 1}));
      EXPECT_EQ(g.free_cells(), 4u);
      EXPECT_EQ(g.format, "npy");
    }
  // One dimension, NumPy's "(n,)" shape; double quotes and Python 2's long literals.
  const OccupancyGrid one =
      parse_npy(npy_file("{\"descr\": \"|u1\", \"fortran_order\": False, \"shape\": (5L,)}",
                         std::string("\x00\x01\x00\x00\x01", 5)),
                "one.npy");
  EXPECT_EQ(one.shape(), (std::vector<int>{5}));
  EXPECT_EQ(one.free_cells(), 3u);
}

TEST(Npy, FortranOrderMatchesTheSameArrayInCOrder) {
  const int n0 = 2, n1 = 3, n2 = 5;  // NumPy shape (2, 3, 5)
  auto blocked = [](int i, int j, int k) { return (i * 7 + j * 3 + k * 5) % 3 == 0; };
  std::string c(n0 * n1 * n2, '\0'), f(n0 * n1 * n2, '\0');
  for (int i = 0; i < n0; ++i)
    for (int j = 0; j < n1; ++j)
      for (int k = 0; k < n2; ++k) {
        c[(i * n1 + j) * n2 + k] = blocked(i, j, k);
        f[i + n0 * (j + n1 * k)] = blocked(i, j, k);
      }
  const OccupancyGrid gc = parse_npy(npy_file(dict("|b1", false, "(2, 3, 5)"), c), "c.npy");
  const OccupancyGrid gf = parse_npy(npy_file(dict("|b1", true, "(2, 3, 5)"), f), "f.npy");
  EXPECT_EQ(gf.shape(), (std::vector<int>{5, 3, 2}));
  for (int i = 0; i < n0; ++i)
    for (int j = 0; j < n1; ++j)
      for (int k = 0; k < n2; ++k) EXPECT_EQ(free_at(gf, {k, j, i}), !blocked(i, j, k));
  EXPECT_EQ(gc.checksum(), gf.checksum());
  // By hand: the 2 x 3 Fortran array [[1, 0, 0], [0, 0, 1]] lies in memory column by column.
  const OccupancyGrid small = parse_npy(
      npy_file(dict("|u1", true, "(2, 3)"), std::string("\x01\x00\x00\x00\x00\x01", 6)), "s.npy");
  EXPECT_FALSE(free_at(small, {0, 0}));
  EXPECT_FALSE(free_at(small, {2, 1}));
  EXPECT_EQ(small.free_cells(), 4u);
}

TEST(Npy, ErrorsNameTheFile) {
  const auto npy = [](const std::string& bytes) {
    return [bytes] { parse_npy(bytes, "bad.npy"); };
  };
  const std::string six(6, '\0');
  EXPECT_TRUE(Fails(npy("PK\x03\x04 a zip file"), {"bad.npy", "\\x93NUMPY"}));
  EXPECT_TRUE(Fails(npy("\x93NUMPY"), {"bad.npy", "\\x93NUMPY"}));
  std::string v4 = npy_file(dict("|u1", false, "(6,)"), six);
  v4[6] = 4;
  EXPECT_TRUE(Fails(npy(v4), {"bad.npy", "version 4.0"}));
  std::string long_header = npy_file(dict("|u1", false, "(6,)"), six);
  long_header[8] = '\xff';
  long_header[9] = '\x7f';
  EXPECT_TRUE(Fails(npy(long_header), {"bad.npy", "header claims 32767 bytes"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("<f4", false, "(6,)"), six)), {"dtype '<f4'"}));
  EXPECT_TRUE(Fails(npy(npy_file("{'descr': '|u1', 'shape': (6,)}", six)), {"'fortran_order'"}));
  EXPECT_TRUE(Fails(npy(npy_file("{'descr': '|u1', 'fortran_order': False, 'shape': (6,), "
                                 "'extra': 1}",
                                 six)),
                    {"unknown key 'extra'"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(6,)") + "junk", six)), {"after the dict"}));
  EXPECT_TRUE(Fails(npy(npy_file("{'descr': '|u1', 'fortran_order': Maybe, 'shape': (6,), }", six)),
                    {"True or False"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(2, x)"), six)), {"whole numbers"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "()"), "\x01")), {"0-dimensional"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(0, 6)"), "")), {"1 to 65535"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(1, 70000)"), "")), {"1 to 65535"}));
  EXPECT_TRUE(
      Fails(npy(npy_file(dict("|u1", false, "(1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1)"), "\x01")),
            {"more than 16 dimensions"}));
  // A claim of 10 GB in a file of under 1 KB: refused before anything is allocated.
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(100000, 100000)"), six)), {"1 to 65535"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|b1", false, "(65535, 65535, 3)"), six)),
                    {"bad.npy", "needs more bytes", "the 6 the file has"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(2, 4)"), six)), {"needs more bytes"}));
  EXPECT_TRUE(Fails(npy(npy_file(dict("|u1", false, "(5,)"), six)), {"1 bytes after the data"}));
}

TEST(Npy, HeaderForAnArrayIsNumPysFormat1) {
  const std::int64_t shape[] = {3, 4};
  const std::string h = npy_header("<f4", shape);
  ASSERT_GE(h.size(), 10u);
  EXPECT_EQ(h.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(h.size() % 64, 0u);
  EXPECT_EQ(static_cast<unsigned char>(h[8]) | (static_cast<unsigned char>(h[9]) << 8),
            h.size() - 10);
  EXPECT_EQ(h.back(), '\n');
  EXPECT_EQ(h.find("{'descr': '<f4', 'fortran_order': False, 'shape': (3, 4), }"), 10u);
  const std::int64_t one[] = {7};
  EXPECT_NE(npy_header("|u1", one).find("'shape': (7,), }"), std::string::npos);
  // What it writes, this reader reads back.
  const std::int64_t box[] = {2, 2, 3};
  const OccupancyGrid g =
      parse_npy(npy_header("|u1", box) + std::string("\x01\0\0\0\0\0\0\0\0\0\0\x01", 12), "w.npy");
  EXPECT_EQ(g.shape(), (std::vector<int>{3, 2, 2}));
  EXPECT_FALSE(free_at(g, {0, 0, 0}));
  EXPECT_FALSE(free_at(g, {2, 1, 1}));
  EXPECT_EQ(g.free_cells(), 10u);
}

// ---- files ------------------------------------------------------------------------------

class OccupancyFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hpcplan_occupancy_io_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  fs::path dir_;
};

TEST_F(OccupancyFiles, LoadsEachFormatByExtension) {
  const OccupancyGrid m =
      load_occupancy(write("a.map", "type octile\nheight 1\nwidth 3\nmap\n.W.\n"), Terrain::water);
  EXPECT_EQ(m.name, "a.map");
  EXPECT_EQ(m.format, "movingai");
  EXPECT_EQ(m.free_cells(), 1u);
  const OccupancyGrid v = load_occupancy(write("b.3dmap", "voxel 2 2 2\n1 1 1\n"));
  EXPECT_EQ(v.name, "b.3dmap");
  EXPECT_EQ(v.format, "voxel");
  EXPECT_EQ(v.free_cells(), 7u);
  const OccupancyGrid n = load_occupancy(
      write("c.NPY", npy_file(dict("|b1", false, "(2,)"), std::string("\x01\x00", 2))));
  EXPECT_EQ(n.name, "c.NPY");
  EXPECT_EQ(n.format, "npy");
  EXPECT_EQ(n.free_cells(), 1u);
  EXPECT_TRUE(
      Fails([&] { load_occupancy(write("d.png", "x")); }, {"d.png", ".map, .3dmap or .npy"}));
  EXPECT_TRUE(Fails([&] { load_occupancy((dir_ / "missing.map").string()); },
                    {"cannot open", "missing.map"}));
  EXPECT_TRUE(Fails([&] { load_occupancy(write("e.map", "type octile\n")); }, {"e.map"}));
  EXPECT_TRUE(Fails([&] { load_occupancy(write("f.npy", "\x93NUMPY\x01")); }, {"f.npy"}));
  EXPECT_EQ(map_format_of("x/y.3DMAP"), MapFormat::voxel);
  EXPECT_EQ(to_string(MapFormat::movingai), "movingai");
  EXPECT_EQ(to_string(MapFormat::voxel), "voxel");
  EXPECT_EQ(to_string(MapFormat::npy), "npy");
  EXPECT_EQ(published_connectivity(MapFormat::movingai), "seed");
  EXPECT_EQ(published_connectivity(MapFormat::voxel), "full");
  EXPECT_EQ(published_connectivity(MapFormat::npy), "");
  // Scenarios by extension.
  const Scenario s =
      load_scenario(write("a.map.scen", "version 1\n0\ta.map\t3\t1\t0\t0\t2\t0\t2\n"));
  EXPECT_FALSE(s.voxel);
  ASSERT_EQ(s.rows.size(), 1u);
  const Scenario s3 =
      load_scenario(write("b.3dmap.3dscen", "version 1\nb.3dmap\n0 0 0 1 1 1 1.73205 1\n"));
  EXPECT_TRUE(s3.voxel);
  EXPECT_EQ(s3.map, "b.3dmap");
}

// ---- scenarios --------------------------------------------------------------------------

TEST(Scenario, ScenRowsTabsCrlfAndVersions) {
  const std::string text =
      "version 1.0\r\n"
      "0\tmaps/dao/arena.map\t49\t49\t1\t11\t1\t12\t1\r\n"
      "3\tmy map.map\t49\t40\t1\t13\t4\t39\t3.41421\r\n"
      "\r\n\r\n";
  const Scenario s = parse_scenario(text, "a.scen", false);
  EXPECT_FALSE(s.voxel);
  EXPECT_EQ(s.version, "1.0");
  EXPECT_EQ(s.map, "maps/dao/arena.map");
  ASSERT_EQ(s.rows.size(), 2u);
  const ScenarioRow& r = s.rows[1];
  EXPECT_EQ(r.bucket, 3);
  EXPECT_EQ(r.map, "my map.map");
  EXPECT_EQ(r.map_size, (std::vector<int>{49, 40}));
  EXPECT_EQ(r.start, (std::vector<int>{1, 13}));
  EXPECT_EQ(r.goal, (std::vector<int>{4, 39}));
  EXPECT_DOUBLE_EQ(r.optimal, 3.41421);
  EXPECT_EQ(r.ratio, 0.0);
  // Whitespace-separated rows (no tab) are read too.
  const Scenario w = parse_scenario("version 1\n2 m.map 8 8 0 0 7 7 9.899\n", "w.scen", false);
  ASSERT_EQ(w.rows.size(), 1u);
  EXPECT_EQ(w.version, "1");
  EXPECT_EQ(w.rows[0].goal, (std::vector<int>{7, 7}));
  // The old format without a version line: 7 columns, no map size.
  const Scenario old = parse_scenario("1 m.map 0 0 3 4 5\n1 m.map 1 1 2 2 1.41\n", "o.scen", false);
  EXPECT_EQ(old.version, "");
  ASSERT_EQ(old.rows.size(), 2u);
  EXPECT_TRUE(old.rows[0].map_size.empty());
  EXPECT_EQ(old.rows[0].goal, (std::vector<int>{3, 4}));
  EXPECT_EQ(parse_scenario("version 1\n", "e.scen", false).rows.size(), 0u);
}

TEST(Scenario, ScenErrorsNameTheFileAndLine) {
  const auto scen = [](const std::string& text) {
    return [text] { parse_scenario(text, "bad.scen", false); };
  };
  const std::string v = "version 1\n";
  EXPECT_TRUE(Fails(scen(""), {"bad.scen", "empty"}));
  EXPECT_TRUE(Fails(scen("version 2\n"), {"bad.scen:1:", "version '2'"}));
  EXPECT_TRUE(Fails(scen("version\n"), {"bad.scen:1:", "version 1"}));
  EXPECT_TRUE(
      Fails(scen(v + "0\tm.map\t8\t8\t0\t0\t1\t1\n"), {"bad.scen:2:", "9 fields", "not 8"}));
  EXPECT_TRUE(Fails(scen(v + "0\tm.map\t8\t8\t0\t0\t1\t1\t1\t1\n"), {"bad.scen:2:", "not more"}));
  EXPECT_TRUE(Fails(scen(v + "x\tm.map\t8\t8\t0\t0\t1\t1\t1\n"), {"bad.scen:2:", "bucket 'x'"}));
  EXPECT_TRUE(
      Fails(scen(v + "-1\tm.map\t8\t8\t0\t0\t1\t1\t1\n"), {"bad.scen:2:", "bucket -1", "range"}));
  EXPECT_TRUE(Fails(scen(v + "0\t\t8\t8\t0\t0\t1\t1\t1\n"), {"bad.scen:2:", "map's name"}));
  EXPECT_TRUE(Fails(scen(v + "0\tm.map\t0\t8\t0\t0\t1\t1\t1\n"), {"map width 0"}));
  EXPECT_TRUE(
      Fails(scen(v + "0\tm.map\t8\t8\t8\t0\t1\t1\t1\n"), {"bad.scen:2:", "start x 8", "range"}));
  EXPECT_TRUE(Fails(scen(v + "0\tm.map\t8\t8\t0\t0\t1\t-1\t1\n"), {"goal y -1", "range"}));
  EXPECT_TRUE(Fails(scen(v + "0\tm.map\t8\t8\t0\t0\t1\ty\t1\n"), {"goal y 'y'", "whole"}));
  EXPECT_TRUE(Fails(scen(v + "\n0\tm.map\t8\t8\t0\t0\t1\t1\t-2\n"), {"bad.scen:3:", "negative"}));
  EXPECT_TRUE(Fails(scen(v + "0\tm.map\t8\t8\t0\t0\t1\t1\tnan\n"), {"'nan'", "finite"}));
  EXPECT_TRUE(Fails(scen(v + std::string(5000, '0') + "\n"), {"bad.scen:2:", "longer than"}));
}

TEST(Scenario, VoxelScenarioRowsAndBuckets) {
  std::string text = "version 1\r\nSimple.3dmap\r\n";
  for (int i = 0; i < 25; ++i)
    text += std::to_string(i) + " 1 2 3 4 5 " + std::to_string(i) + ".5 1.25\r\n";
  text += "\r\n";
  const Scenario s = parse_scenario(text, "s.3dscen", true);
  EXPECT_TRUE(s.voxel);
  EXPECT_EQ(s.version, "1");
  EXPECT_EQ(s.map, "Simple.3dmap");
  ASSERT_EQ(s.rows.size(), 25u);
  EXPECT_EQ(s.rows[9].bucket, 0);
  EXPECT_EQ(s.rows[10].bucket, 1);
  EXPECT_EQ(s.rows[24].bucket, 2);
  EXPECT_EQ(s.rows[7].start, (std::vector<int>{7, 1, 2}));
  EXPECT_EQ(s.rows[7].goal, (std::vector<int>{3, 4, 5}));
  EXPECT_DOUBLE_EQ(s.rows[7].optimal, 7.5);
  EXPECT_DOUBLE_EQ(s.rows[7].ratio, 1.25);
  EXPECT_EQ(s.rows[7].map, "Simple.3dmap");
  EXPECT_TRUE(s.rows[7].map_size.empty());
}

TEST(Scenario, VoxelScenarioErrors) {
  const auto scen = [](const std::string& text) {
    return [text] { parse_scenario(text, "bad.3dscen", true); };
  };
  const std::string h = "version 1\nm.3dmap\n";
  EXPECT_TRUE(Fails(scen("m.3dmap\n0 0 0 1 1 1 1.7 1\n"), {"bad.3dscen:1:", "version 1"}));
  EXPECT_TRUE(Fails(scen("version 1\n"), {"bad.3dscen", "naming the map"}));
  EXPECT_TRUE(Fails(scen("version 1\n0 0 0 1 1 1 1.7 1\n"), {"bad.3dscen:2:", "names the map"}));
  EXPECT_TRUE(Fails(scen(h + "0 0 0 1 1 1 1.7\n"), {"bad.3dscen:3:", "8 fields", "not 7"}));
  EXPECT_TRUE(Fails(scen(h + "0 0 -1 1 1 1 1.7 1\n"), {"bad.3dscen:3:", "start z -1", "range"}));
  EXPECT_TRUE(Fails(scen(h + "0 0 0 1 65535 1 1.7 1\n"), {"goal y 65535", "range"}));
  EXPECT_TRUE(Fails(scen(h + "0 0 0 1 1 1 -1.7 1\n"), {"bad.3dscen:3:", "negative"}));
  EXPECT_TRUE(Fails(scen(h + "0 0 0 1 1 1 1.7 x\n"), {"heuristic ratio 'x'"}));
  EXPECT_TRUE(Fails(scen(h + "0 0 0 1 1 1 1.7 -1\n"), {"heuristic ratio", "negative"}));
}

// ---- the shared MovingAI benchmarks -------------------------------------------------------

std::string movingai_dir() {
  if (const char* dir = std::getenv("HPCPLAN_MOVINGAI_DIR"); dir && *dir) return dir;
  return HPCPLAN_MOVINGAI_DIR;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(MovingAiBenchmarks, FourMapsAndTheirScenariosLoad) {
  const std::string dir = movingai_dir();
  ASSERT_TRUE(fs::is_directory(dir))
      << "the MovingAI benchmark folder '" << dir
      << "' is missing (configure with -DHPCPLAN_MOVINGAI_DIR=..., or set the environment "
         "variable HPCPLAN_MOVINGAI_DIR)";
  struct Case {
    const char* map;
    int side;
    std::size_t rows;  // the folder's README
  };
  for (const Case c : {Case{"random512-40-5.map", 512, 5240}, Case{"maze512-4-6.map", 512, 13720},
                       Case{"64room_005.map", 512, 2320}, Case{"Boston_0_256.map", 256, 950}}) {
    SCOPED_TRACE(c.map);
    const std::string path = dir + "/" + c.map;
    const std::string text = read_file(path);
    ASSERT_FALSE(text.empty()) << path;
    const auto t0 = std::chrono::steady_clock::now();
    const OccupancyGrid g = load_occupancy(path);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    RecordProperty(std::string(c.map) + "_load_ms", std::to_string(ms));
    EXPECT_EQ(g.shape(), (std::vector<int>{c.side, c.side}));
    EXPECT_EQ(g.name, c.map);
    // The free cells are the ground characters after the "map" line, counted independently.
    const std::size_t body = text.find("map", text.find("width"));
    const std::size_t ground =
        std::count_if(text.begin() + static_cast<std::ptrdiff_t>(text.find('\n', body)), text.end(),
                      [](char ch) { return ch == '.' || ch == 'G' || ch == 'S'; });
    EXPECT_EQ(g.free_cells(), ground);

    const std::string scen_text = read_file(path + ".scen");
    std::size_t lines = 0;
    std::istringstream in(scen_text);
    for (std::string line; std::getline(in, line);)
      lines += line.find_first_not_of(" \t\r") != std::string::npos;
    const Scenario s = load_scenario(path + ".scen");
    EXPECT_EQ(s.rows.size(), lines - 1);  // less the version line
    EXPECT_EQ(s.rows.size(), c.rows);
    EXPECT_EQ(s.version, "1");
    EXPECT_EQ(s.map, c.map);
    // Every problem lies on the map, its ends on free cells (x the column, y the row).
    std::size_t off_map = 0, blocked = 0;
    for (const ScenarioRow& r : s.rows) {
      off_map += r.map_size != std::vector<int>{c.side, c.side};
      blocked += !g.is_free(r.start) + !g.is_free(r.goal);
    }
    EXPECT_EQ(off_map, 0u);
    EXPECT_EQ(blocked, 0u);
  }
}

}  // namespace
}  // namespace hpcplan::env
