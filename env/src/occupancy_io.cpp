// The occupancy files (occupancy_io.hpp): MovingAI .map, voxel .3dmap, NumPy .npy, and the
// scenario files that go with the first two. Every parser walks its text once, without a
// per-line or per-cell allocation, and checks a size claim against the bytes that are there
// before it allocates the grid.
#include "hpcplan/env/occupancy_io.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/text_lines.hpp"

namespace hpcplan::env {
namespace {

constexpr int kMaxSide = 65535;  // as OccupancyGrid's sides
constexpr int kMaxDims = 16;     // as OccupancyGrid's dimensions

[[noreturn]] void fail(const std::string& name, int line, const std::string& message) {
  throw InputError(one_line(where(name, line) + message));
}
[[noreturn]] void fail(const std::string& name, const std::string& message) {
  throw InputError(one_line(name + ": " + message));
}

// A word for a message: at most 40 bytes, anything unprintable as \xNN.
std::string shown(std::string_view w) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "'";
  for (std::size_t i = 0; i < w.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(w[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (w.size() > 40) out += "...";
  return out + "'";
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

std::string_view trim_right(std::string_view s) {
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}
std::string_view trim(std::string_view s) {
  s = trim_right(s);
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

// The text's lines one at a time ('\n' removed, '\r' kept for the caller's trim), numbered
// from 1.
struct Lines {
  std::string_view rest;
  int number = 0;
  bool next(std::string_view& line) {
    if (rest.empty()) return false;
    const void* nl = std::memchr(rest.data(), '\n', rest.size());
    const std::size_t end =
        nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - rest.data()) : rest.size();
    line = rest.substr(0, end);
    rest = nl ? rest.substr(end + 1) : std::string_view{};
    ++number;
    return true;
  }
  // The next line with something other than white space, trimmed; false at the end.
  bool next_nonblank(std::string_view& line) {
    while (next(line)) {
      line = trim(line);
      if (!line.empty()) return true;
    }
    return false;
  }
};

// Splits at spaces and tabs into at most `max` words; returns how many there are (max + 1 when
// there are more).
int split_words(std::string_view line, std::string_view* words, int max) {
  int n = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i == line.size()) break;
    std::size_t j = i;
    while (j < line.size() && !is_space(line[j])) ++j;
    if (n == max) return max + 1;
    words[n++] = line.substr(i, j - i);
    i = j;
  }
  return n;
}

// A whole number, all of the word (an optional sign, digits); false otherwise or on overflow.
bool to_int(std::string_view w, long long& v) {
  const char* first = w.data();
  const char* last = w.data() + w.size();
  if (first != last && *first == '+') ++first;
  if (first == last || *first == '+' || (first != w.data() && *first == '-')) return false;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  return ec == std::errc{} && ptr == last;
}

long long whole(std::string_view w, const std::string& name, int line, const char* what) {
  long long v = 0;
  if (!to_int(w, v))
    fail(name, line, std::string(what) + " " + shown(w) + " is not a whole number");
  return v;
}

int side(std::string_view w, const std::string& name, int line, const char* what) {
  const long long v = whole(w, name, line, what);
  if (v < 1 || v > kMaxSide)
    fail(
        name, line,
        std::string(what) + " " + std::to_string(v) + " is outside 1.." + std::to_string(kMaxSide));
  return static_cast<int>(v);
}

double finite(std::string_view w, const std::string& name, int line, const char* what) {
  double v = 0.0;
  const char* first = w.data();
  const char* last = w.data() + w.size();
  if (first != last && *first == '+') ++first;
  const bool signs = first != w.data() && first != last && *first == '-';
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (first == last || signs || ec != std::errc{} || ptr != last || !std::isfinite(v))
    fail(name, line, std::string(what) + " " + shown(w) + " is not a finite number");
  return v;
}

// The grid `make` builds, its InputError (a shape this machine's memory cannot hold) naming
// the file.
template <class Make>
OccupancyGrid named(const std::string& name, Make&& make) {
  try {
    return make();
  } catch (const InputError& e) {
    fail(name, e.what());
  }
}

// ---- .map -------------------------------------------------------------------------------

enum CellClass : std::uint8_t { kGround, kBlocked, kWater, kUnknown };

constexpr std::array<std::uint8_t, 256> kCellClass = [] {
  std::array<std::uint8_t, 256> t{};
  t.fill(kUnknown);
  for (unsigned char c : {'.', 'G', 'S'}) t[c] = kGround;
  for (unsigned char c : {'@', 'O', 'T'}) t[c] = kBlocked;
  t['W'] = kWater;
  return t;
}();

struct MapHeader {
  int width = 0, height = 0;
  Lines rows;  // positioned after the "map" line
};

MapHeader read_map_header(std::string_view text, const std::string& name) {
  MapHeader h;
  h.rows.rest = text;
  Lines& lines = h.rows;
  std::string_view line, w[3];
  if (!lines.next_nonblank(line)) fail(name, "empty file; a .map begins with 'type octile'");
  if (split_words(line, w, 2) != 2 || !iequals(w[0], "type"))
    fail(name, lines.number, "a .map begins with 'type octile', not " + shown(line));
  while (true) {
    if (!lines.next_nonblank(line))
      fail(name, "the header ends without a 'map' line (type, height, width, map)");
    const int n = split_words(line, w, 2);
    if (n == 1 && iequals(w[0], "map")) break;
    const bool height = n == 2 && iequals(w[0], "height");
    if (!height && !(n == 2 && iequals(w[0], "width")))
      fail(name, lines.number,
           "expected 'height H', 'width W' or 'map' in the header, not " + shown(line));
    int& slot = height ? h.height : h.width;
    if (slot)
      fail(name, lines.number,
           std::string("a second '") + (height ? "height" : "width") + "' line");
    slot = side(w[1], name, lines.number, height ? "height" : "width");
  }
  if (!h.height || !h.width)
    fail(name, lines.number,
         std::string("'map' before the header's '") + (h.height ? "width" : "height") + "' line");
  return h;
}

// ---- .npy -------------------------------------------------------------------------------

struct NpyHeader {
  std::string descr;
  bool fortran = false;
  std::vector<std::int64_t> shape;
};

// The header's Python dict literal: {'descr': ..., 'fortran_order': ..., 'shape': (...), }.
class NpyDict {
 public:
  NpyDict(std::string_view s, const std::string& name) : s_(s), name_(name) {}

  NpyHeader parse() {
    NpyHeader h;
    bool seen[3] = {false, false, false};
    ws();
    expect('{');
    while (true) {
      ws();
      if (peek() == '}') {
        ++i_;
        break;
      }
      const std::string_view key = string();
      ws();
      expect(':');
      ws();
      int k = -1;
      if (key == "descr") {
        k = 0;
        h.descr = std::string(string());
      } else if (key == "fortran_order") {
        k = 1;
        h.fortran = boolean();
      } else if (key == "shape") {
        k = 2;
        h.shape = tuple();
      } else {
        bad("unknown key " + shown(key) + " (descr, fortran_order, shape)");
      }
      if (seen[k]) bad("a second " + shown(key));
      seen[k] = true;
      ws();
      if (peek() == ',') {
        ++i_;
      } else if (peek() != '}') {
        bad("expected ',' or '}' after the value of " + shown(key));
      }
    }
    ws();
    if (i_ != s_.size()) bad("text after the dict's '}'");
    static constexpr const char* kKeys[] = {"descr", "fortran_order", "shape"};
    for (int k = 0; k < 3; ++k)
      if (!seen[k]) bad(std::string("no '") + kKeys[k] + "' key");
    return h;
  }

 private:
  [[noreturn]] void bad(const std::string& message) const {
    fail(name_, ".npy header: " + message);
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void ws() {
    while (i_ < s_.size() && (is_space(s_[i_]) || s_[i_] == '\n')) ++i_;
  }
  void expect(char c) {
    if (peek() != c) bad(std::string("expected '") + c + "' at byte " + std::to_string(i_));
    ++i_;
  }
  std::string_view string() {
    const char q = peek();
    if (q != '\'' && q != '"') bad("expected a quoted string at byte " + std::to_string(i_));
    const std::size_t end = s_.find(q, i_ + 1);
    if (end == std::string_view::npos) bad("a string without its closing quote");
    const std::string_view v = s_.substr(i_ + 1, end - i_ - 1);
    i_ = end + 1;
    return v;
  }
  bool boolean() {
    if (s_.substr(i_, 4) == "True") {
      i_ += 4;
      return true;
    }
    if (s_.substr(i_, 5) == "False") {
      i_ += 5;
      return false;
    }
    bad("fortran_order is True or False");
  }
  std::vector<std::int64_t> tuple() {
    std::vector<std::int64_t> v;
    expect('(');
    while (true) {
      ws();
      if (peek() == ')') {
        ++i_;
        return v;
      }
      if (peek() < '0' || peek() > '9') bad("the shape is a tuple of whole numbers");
      std::int64_t n = 0;
      while (peek() >= '0' && peek() <= '9') {
        if (n > (std::numeric_limits<std::int64_t>::max() - 9) / 10)
          bad("a side of the shape is too large");
        n = n * 10 + (peek() - '0');
        ++i_;
      }
      if (peek() == 'L') ++i_;  // Python 2's long literals
      if (v.size() == static_cast<std::size_t>(kMaxDims)) bad("more than 16 dimensions");
      v.push_back(n);
      ws();
      if (peek() == ',') {
        ++i_;
      } else if (peek() != ')') {
        bad("expected ',' or ')' in the shape");
      }
    }
  }

  std::string_view s_;
  const std::string& name_;
  std::size_t i_ = 0;
};

std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(shape[i]);
  }
  return s + (shape.size() == 1 ? ",)" : ")");
}

// ---- files ------------------------------------------------------------------------------

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return ext;
}

// A binary file whole, refused past `cap` bytes (checked before reading where the size is
// known, as it is for a regular file; a pipe or device is read in chunks up to the cap).
std::string read_binary_file(const std::string& path, std::uint64_t cap, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(one_line(std::string("cannot open ") + what + " '" + path + "'"));
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  std::string bytes;
  if (!ec && std::filesystem::is_regular_file(status)) {
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (!ec) {
      if (size > cap)
        throw InputError(one_line(std::string(what) + " '" + path + "' is larger than " +
                                  std::to_string(cap >> 20) + " MiB"));
      bytes.resize(static_cast<std::size_t>(size));
      in.read(bytes.data(), static_cast<std::streamsize>(size));
      if (static_cast<std::uint64_t>(in.gcount()) != size)
        throw InputError(one_line(std::string("cannot read ") + what + " '" + path + "'"));
      return bytes;
    }
  }
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    bytes.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (bytes.size() > cap)
      throw InputError(one_line(std::string(what) + " '" + path + "' is larger than " +
                                std::to_string(cap >> 20) + " MiB"));
  }
  if (in.bad()) throw InputError(one_line(std::string("cannot read ") + what + " '" + path + "'"));
  return bytes;
}

constexpr std::uint64_t kMaxNpyFileBytes = std::uint64_t{4} << 30;  // 4 GiB
constexpr std::size_t kMaxNpyHeaderBytes = std::size_t{1} << 20;    // NumPy's own are < 64 KiB

}  // namespace

// ---- formats ----------------------------------------------------------------------------

MapFormat map_format_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".map") return MapFormat::movingai;
  if (ext == ".3dmap") return MapFormat::voxel;
  if (ext == ".npy") return MapFormat::npy;
  throw InputError(
      one_line("'" + path + "': an occupancy file is a .map, .3dmap or .npy, not " +
               (ext.empty() ? std::string("a file without an extension") : shown(ext))));
}

std::string_view to_string(MapFormat f) {
  switch (f) {
    case MapFormat::movingai:
      return "movingai";
    case MapFormat::voxel:
      return "voxel";
    case MapFormat::npy:
      return "npy";
  }
  return "?";
}

std::string_view published_connectivity(MapFormat f) {
  switch (f) {
    case MapFormat::movingai:
      return "seed";
    case MapFormat::voxel:
      return "full";
    case MapFormat::npy:
      return "";
  }
  return "";
}

// ---- .map -------------------------------------------------------------------------------

OccupancyGrid parse_movingai_map(std::string_view text, const std::string& name, Terrain terrain) {
  MapHeader h = read_map_header(text, name);
  Lines& lines = h.rows;
  // Each row holds at least W bytes: a claim the text cannot hold is refused here, before the
  // grid is allocated.
  const std::uint64_t need =
      static_cast<std::uint64_t>(h.width) * static_cast<std::uint64_t>(h.height);
  if (lines.rest.size() < need)
    fail(name, lines.number,
         "the header claims " + std::to_string(h.height) + " rows of " + std::to_string(h.width) +
             " cells (" + std::to_string(need) + " bytes) but only " +
             std::to_string(lines.rest.size()) + " bytes follow 'map'");
  OccupancyGrid grid = named(name, [&] { return OccupancyGrid({h.width, h.height}); });
  const std::uint8_t free_class = terrain == Terrain::water ? kWater : kGround;
  const std::uint64_t row_bits = static_cast<std::uint64_t>(grid.stride(1));
  const std::size_t width = static_cast<std::size_t>(h.width);
  std::string_view line;
  for (int y = 0; y < h.height; ++y) {
    if (!lines.next(line))
      fail(name, "the file ends after " + std::to_string(y) + " of the " +
                     std::to_string(h.height) + " rows the header claims");
    line = trim_right(line);
    if (line.size() != width)
      fail(name, lines.number,
           "row " + std::to_string(y) + " has " + std::to_string(line.size()) + " cells, " +
               (line.size() < width ? "short of" : "longer than") + " the width " +
               std::to_string(h.width));
    const std::uint64_t base = static_cast<std::uint64_t>(y) * row_bits;
    for (std::size_t x = 0; x < width; ++x) {
      const std::uint8_t c = kCellClass[static_cast<unsigned char>(line[x])];
      if (c == free_class) continue;
      if (c == kUnknown)
        fail(name, lines.number,
             "unknown character " + shown(line.substr(x, 1)) + " in row " + std::to_string(y) +
                 " column " + std::to_string(x) + " (a .map has . G S @ O T W)");
      grid.block_at(base + x);
    }
  }
  while (lines.next(line))
    if (!trim(line).empty())
      fail(name, lines.number,
           "text after the " + std::to_string(h.height) +
               " rows the header claims (a row too many?): " + shown(trim(line)));
  grid.name = name;
  grid.format = "movingai";
  grid.seal();
  return grid;
}

std::optional<char> movingai_cell(std::string_view text, int x, int y) {
  MapHeader h;
  try {
    h = read_map_header(text, "map");
  } catch (const InputError&) {
    return std::nullopt;
  }
  if (x < 0 || y < 0 || x >= h.width || y >= h.height) return std::nullopt;
  std::string_view line;
  for (int row = 0; row <= y; ++row)
    if (!h.rows.next(line)) return std::nullopt;
  line = trim_right(line);
  if (static_cast<std::size_t>(x) >= line.size()) return std::nullopt;
  return line[static_cast<std::size_t>(x)];
}

// ---- .3dmap -----------------------------------------------------------------------------

OccupancyGrid parse_voxel_map(std::string_view text, const std::string& name,
                              std::uint64_t max_grid_bytes) {
  Lines lines{text};
  std::string_view line, w[4];
  if (!lines.next_nonblank(line)) fail(name, "empty file; a .3dmap begins with 'voxel W H D'");
  if (split_words(line, w, 4) != 4 || !iequals(w[0], "voxel"))
    fail(name, lines.number, "a .3dmap begins with 'voxel W H D', not " + shown(line));
  const int sx = side(w[1], name, lines.number, "width");
  const int sy = side(w[2], name, lines.number, "height");
  const int sz = side(w[3], name, lines.number, "depth");
  // The grid's bytes as OccupancyGrid stores it (rows along x padded to 64 voxels): a list of
  // blocked voxels need not hold its box, so the header alone is checked, before allocating.
  const std::uint64_t bytes = (static_cast<std::uint64_t>(sx) + 63) / 64 * 8 *
                              static_cast<std::uint64_t>(sy) * static_cast<std::uint64_t>(sz);
  if (bytes > max_grid_bytes)
    fail(name, lines.number,
         "voxel " + std::to_string(sx) + " " + std::to_string(sy) + " " + std::to_string(sz) +
             " needs a grid of " + std::to_string(bytes) + " bytes, more than the " +
             std::to_string(max_grid_bytes) + " this reader accepts");
  OccupancyGrid grid = named(name, [&] { return OccupancyGrid({sx, sy, sz}); });
  const std::uint64_t sy_bits = static_cast<std::uint64_t>(grid.stride(1));
  const std::uint64_t sz_bits = static_cast<std::uint64_t>(grid.stride(2));
  const long long limit[3] = {sx, sy, sz};
  while (lines.next(line)) {
    const int n = split_words(line, w, 3);
    if (n == 0) continue;
    if (n != 3) fail(name, lines.number, "a voxel line is 'x y z', not " + shown(trim(line)));
    long long c[3];
    for (int a = 0; a < 3; ++a) {
      if (!to_int(w[a], c[a]))
        fail(name, lines.number, "voxel coordinate " + shown(w[a]) + " is not a whole number");
    }
    for (int a = 0; a < 3; ++a)
      if (c[a] < 0 || c[a] >= limit[a])
        fail(name, lines.number,
             "voxel (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
                 std::to_string(c[2]) + ") is out of range: outside the " + std::to_string(sx) +
                 " x " + std::to_string(sy) + " x " + std::to_string(sz) + " box");
    grid.block_at(static_cast<std::uint64_t>(c[0]) + static_cast<std::uint64_t>(c[1]) * sy_bits +
                  static_cast<std::uint64_t>(c[2]) * sz_bits);
  }
  grid.name = name;
  grid.format = "voxel";
  grid.seal();
  return grid;
}

// ---- .npy -------------------------------------------------------------------------------

OccupancyGrid parse_npy(std::string_view bytes, const std::string& name) {
  static constexpr char kMagic[] = "\x93NUMPY";
  if (bytes.size() < 10 || bytes.substr(0, 6) != std::string_view(kMagic, 6))
    fail(name, "not a .npy file (it does not begin with the \\x93NUMPY magic)");
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(bytes[i]); };
  const int major = byte(6), minor = byte(7);
  if (major < 1 || major > 3 || minor != 0)
    fail(name, "unsupported .npy format version " + std::to_string(major) + "." +
                   std::to_string(minor) + " (1.0, 2.0 and 3.0 are read)");
  std::size_t start = 10;
  std::uint64_t header_len = byte(8) | (std::uint64_t{byte(9)} << 8);
  if (major >= 2) {
    if (bytes.size() < 12) fail(name, "the file ends inside the .npy preamble");
    header_len |= (std::uint64_t{byte(10)} << 16) | (std::uint64_t{byte(11)} << 24);
    start = 12;
  }
  if (header_len > bytes.size() - start)
    fail(name, "the .npy header claims " + std::to_string(header_len) + " bytes but the file has " +
                   std::to_string(bytes.size() - start) + " after the preamble");
  if (header_len > kMaxNpyHeaderBytes)
    fail(name, "a .npy header of " + std::to_string(header_len) + " bytes; more than the " +
                   std::to_string(kMaxNpyHeaderBytes) + " this reader accepts");
  const NpyHeader h =
      NpyDict(bytes.substr(start, static_cast<std::size_t>(header_len)), name).parse();

  static constexpr std::string_view kBool[] = {"|b1", "b1", "<b1", ">b1", "=b1", "?", "bool"};
  static constexpr std::string_view kU8[] = {"|u1", "u1", "<u1", ">u1", "=u1", "B", "uint8"};
  if (std::find(std::begin(kBool), std::end(kBool), h.descr) == std::end(kBool) &&
      std::find(std::begin(kU8), std::end(kU8), h.descr) == std::end(kU8))
    fail(name, "dtype " + shown(h.descr) + " is neither bool (|b1) nor uint8 (|u1)");
  const std::size_t d = h.shape.size();
  if (d == 0) fail(name, "a 0-dimensional array (a scalar) is not an occupancy grid");
  for (std::int64_t s : h.shape)
    if (s < 1 || s > kMaxSide)
      fail(name, "shape " + shape_text(h.shape) + ": its sides must be 1 to " +
                     std::to_string(kMaxSide) + " cells");
  // The data must be all there: a claim larger than the file is refused before the grid is
  // allocated (each side is at most 65535 and the running product stops at the file's size,
  // so it never overflows).
  const std::size_t offset = start + static_cast<std::size_t>(header_len);
  const std::uint64_t have = bytes.size() - offset;
  unsigned __int128 need = 1;
  for (std::int64_t s : h.shape) {
    need *= static_cast<std::uint64_t>(s);
    if (need > have) break;
  }
  if (need > have)
    fail(name, "the shape " + shape_text(h.shape) + " needs more bytes of data than the " +
                   std::to_string(have) + " the file has after its header");
  const auto total = static_cast<std::uint64_t>(need);
  if (have > total)
    fail(name, "the file has " + std::to_string(have - total) + " bytes after the data of its " +
                   shape_text(h.shape) + " array");
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data() + offset);

  if (!h.fortran || d == 1) {
    OccupancyGrid grid = named(name, [&] { return occupancy_from_bytes(data, h.shape); });
    grid.name = name;
    grid.format = "npy";
    grid.seal();
    return grid;
  }
  // Fortran order: the array's first axis varies fastest in memory, and array axis k is the
  // grid's axis d-1-k. Walk the bytes in memory order, an odometer over the other axes.
  std::vector<int> shape(d);
  for (std::size_t a = 0; a < d; ++a) shape[a] = static_cast<int>(h.shape[d - 1 - a]);
  OccupancyGrid grid = named(name, [&] { return OccupancyGrid(std::move(shape)); });
  std::vector<std::uint64_t> step(d);
  for (std::size_t k = 0; k < d; ++k)
    step[k] = static_cast<std::uint64_t>(grid.stride(static_cast<int>(d - 1 - k)));
  std::vector<std::int64_t> index(d, 0);
  const auto n0 = static_cast<std::uint64_t>(h.shape[0]);
  std::uint64_t base = 0;
  for (std::uint64_t run = 0; run < total / n0; ++run) {
    const std::uint8_t* src = data + run * n0;
    for (std::uint64_t i = 0; i < n0; ++i)
      if (src[i]) grid.block_at(base + i * step[0]);
    for (std::size_t k = 1; k < d; ++k) {
      if (++index[k] < h.shape[k]) {
        base += step[k];
        break;
      }
      base -= static_cast<std::uint64_t>(h.shape[k] - 1) * step[k];
      index[k] = 0;
    }
  }
  grid.name = name;
  grid.format = "npy";
  grid.seal();
  return grid;
}

std::string npy_header(std::string_view dtype, std::span<const std::int64_t> shape) {
  std::string dict = "{'descr': '" + std::string(dtype) + "', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i) dict += ", ";
    dict += std::to_string(shape[i]);
  }
  dict += shape.size() == 1 ? ",), }" : "), }";
  // Padded with spaces so that the data starts at a multiple of 64 bytes, '\n' last.
  std::size_t preamble = 10;
  if ((preamble + dict.size() + 1 + 63) / 64 * 64 - preamble > 65535) preamble = 12;
  const std::size_t total = (preamble + dict.size() + 1 + 63) / 64 * 64;
  dict.append(total - preamble - dict.size() - 1, ' ');
  dict += '\n';
  const std::size_t len = dict.size();
  std::string out = "\x93NUMPY";
  out += static_cast<char>(preamble == 10 ? 1 : 2);
  out += '\0';
  for (std::size_t i = 0; i < preamble - 8; ++i) out += static_cast<char>((len >> (8 * i)) & 0xFF);
  return out + dict;
}

OccupancyGrid load_occupancy(const std::string& path, Terrain terrain) {
  const MapFormat format = map_format_of(path);
  OccupancyGrid grid = [&] {
    switch (format) {
      case MapFormat::movingai:
        return parse_movingai_map(read_text_file(path, "map file"), path, terrain);
      case MapFormat::voxel:
        return parse_voxel_map(read_text_file(path, "voxel map file"), path);
      case MapFormat::npy:
        break;
    }
    return parse_npy(read_binary_file(path, kMaxNpyFileBytes, ".npy file"), path);
  }();
  grid.name = std::filesystem::path(path).filename().string();
  grid.format = std::string(to_string(format));
  return grid;  // sealed by its parser (the name and format are not in the checksum)
}

// ---- scenarios --------------------------------------------------------------------------

namespace {

constexpr int kScenFields = 9, kOldScenFields = 7, kVoxelScenFields = 8;

// Splits a .scen row: at tabs when it has any (a map name may hold spaces), otherwise at white
// space. Returns the number of fields (max + 1 when there are more).
int split_scen(std::string_view line, std::string_view* f, int max) {
  if (line.find('\t') == std::string_view::npos) return split_words(line, f, max);
  int n = 0;
  while (true) {
    const std::size_t tab = line.find('\t');
    if (n == max) return max + 1;
    f[n++] = trim(line.substr(0, tab));
    if (tab == std::string_view::npos) return n;
    line = line.substr(tab + 1);
  }
}

void check_version(std::string_view word, const std::string& name, int line) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (ec != std::errc{} || ptr != word.data() + word.size() || v != 1.0)
    fail(name, line, "scenario version " + shown(word) + " is not 1 (or 1.0)");
}

int coordinate(std::string_view w, int size, const std::string& name, int line, const char* what) {
  const long long v = whole(w, name, line, what);
  if (v < 0 || v >= size)
    fail(name, line,
         std::string(what) + " " + std::to_string(v) + " is out of range 0.." +
             std::to_string(size - 1));
  return static_cast<int>(v);
}

double optimal_length(std::string_view w, const std::string& name, int line) {
  const double v = finite(w, name, line, "optimal length");
  if (v < 0) fail(name, line, "optimal length " + shown(w) + " is negative");
  return v;
}

}  // namespace

Scenario parse_scenario(std::string_view text, const std::string& name, bool voxel) {
  Scenario sc;
  sc.voxel = voxel;
  Lines lines{text};
  std::string_view line;
  std::string_view f[kScenFields + 1];
  bool pending = false;  // an old-format .scen: the first line is already a row
  if (!lines.next_nonblank(line))
    fail(name, voxel ? "empty file; a .3dscen begins with 'version 1'"
                     : "empty file; a .scen begins with 'version 1'");
  if (line.size() > kMaxLineBytes)
    fail(name, lines.number, "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
  {
    const int n = split_words(line, f, 2);
    if (n >= 1 && iequals(f[0], "version")) {
      if (n != 2) fail(name, lines.number, "the version line is 'version 1', not " + shown(line));
      check_version(f[1], name, lines.number);
      sc.version = std::string(f[1]);
    } else if (voxel) {
      fail(name, lines.number, "a .3dscen begins with 'version 1', not " + shown(line));
    } else {
      pending = true;
    }
  }
  if (voxel) {
    if (!lines.next_nonblank(line)) fail(name, "no line naming the map after the version line");
    if (line.size() > kMaxLineBytes)
      fail(name, lines.number, "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
    // A problem row where the map's name belongs: a file without its map line.
    long long ignored = 0;
    if (split_words(line, f, kVoxelScenFields) == kVoxelScenFields && to_int(f[0], ignored) &&
        to_int(f[1], ignored) && to_int(f[2], ignored))
      fail(name, lines.number, "the line after the version names the map, not a problem");
    sc.map = std::string(line);
  }
  const int want = voxel ? kVoxelScenFields : sc.version.empty() ? kOldScenFields : kScenFields;
  while (pending || lines.next(line)) {
    if (!pending) line = trim(line);
    pending = false;
    if (line.empty()) continue;
    if (line.size() > kMaxLineBytes)
      fail(name, lines.number, "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
    const int n = voxel ? split_words(line, f, want) : split_scen(line, f, want);
    if (n != want)
      fail(name, lines.number,
           "a row has " + std::to_string(want) + " fields (" +
               (voxel                 ? "sx sy sz gx gy gz optimal ratio"
                : want == kScenFields ? "bucket map width height sx sy gx gy optimal"
                                      : "bucket map sx sy gx gy optimal") +
               "), not " + (n > want ? "more" : std::to_string(n)));
    ScenarioRow row;
    const int at = lines.number;
    if (voxel) {
      row.bucket = static_cast<int>(sc.rows.size() / 10);
      row.map = sc.map;
      static constexpr const char* kWhat[] = {"start x", "start y", "start z",
                                              "goal x",  "goal y",  "goal z"};
      for (int a = 0; a < 6; ++a)
        (a < 3 ? row.start : row.goal).push_back(coordinate(f[a], kMaxSide, name, at, kWhat[a]));
      row.optimal = optimal_length(f[6], name, at);
      row.ratio = finite(f[7], name, at, "heuristic ratio");
      if (row.ratio < 0) fail(name, at, "heuristic ratio " + shown(f[7]) + " is negative");
    } else {
      const long long bucket = whole(f[0], name, at, "bucket");
      if (bucket < 0 || bucket > std::numeric_limits<int>::max())
        fail(name, at, "bucket " + std::to_string(bucket) + " is out of range (0 and up)");
      row.bucket = static_cast<int>(bucket);
      if (f[1].empty()) fail(name, at, "a row without its map's name");
      row.map = std::string(f[1]);
      int c = 2, width = kMaxSide + 1, height = kMaxSide + 1;
      if (want == kScenFields) {
        width = side(f[2], name, at, "map width");
        height = side(f[3], name, at, "map height");
        row.map_size = {width, height};
        c = 4;
      }
      row.start = {coordinate(f[c], width, name, at, "start x"),
                   coordinate(f[c + 1], height, name, at, "start y")};
      row.goal = {coordinate(f[c + 2], width, name, at, "goal x"),
                  coordinate(f[c + 3], height, name, at, "goal y")};
      row.optimal = optimal_length(f[c + 4], name, at);
      if (sc.rows.empty()) sc.map = row.map;
    }
    sc.rows.push_back(std::move(row));
  }
  return sc;
}

Scenario load_scenario(const std::string& path) {
  const bool voxel = lower_extension(path) == ".3dscen";
  return parse_scenario(read_text_file(path, "scenario file"), path, voxel);
}

}  // namespace hpcplan::env
