#pragma once
// Line-oriented parsing shared by the world file formats: comments, CRLF, whitespace
// splitting and strict finite numbers, with errors that name the file and line.
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/core/error.hpp"

namespace hpcplan::env {

// Limits on what a world file may be, so a wrong path (/dev/zero, a core dump) is refused with
// one line instead of growing memory without end. The shipped maps are under 16 KiB.
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;
inline constexpr std::size_t kMaxLineBytes = 4096;

inline std::string where(const std::string& name, int line) {
  return name + ":" + std::to_string(line) + ": ";
}

// Calls fn(line number, words) for every line that has words after comments are removed.
// `name` is the file's name for errors.
template <class Fn>
void for_each_directive(std::string_view text, const std::string& name, Fn&& fn) {
  int number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++number;
    if (line.size() > kMaxLineBytes)
      throw InputError(where(name, number) + "line longer than " + std::to_string(kMaxLineBytes) +
                       " bytes; is this a world file?");
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
      if (j > i) words.push_back(line.substr(i, j - i));
      i = j;
    }
    if (!words.empty()) fn(number, words);
  }
}

inline double parse_number(std::string_view word, const std::string& name, int line) {
  double v = 0.0;
  const char* first = word.data();
  if (!word.empty() && word.front() == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, word.data() + word.size(), v);
  if (ec != std::errc{} || ptr != word.data() + word.size() || !std::isfinite(v))
    throw InputError(where(name, line) + "'" + std::string(word) + "' is not a finite number");
  return v;
}

inline std::string read_text_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(std::string("cannot open ") + what + " '" + path + "'");
  // Read in chunks up to the cap: a device or pipe has no size to ask for beforehand.
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxTextFileBytes)
      throw InputError(std::string(what) + " '" + path + "' is larger than " +
                       std::to_string(kMaxTextFileBytes >> 20) + " MiB");
  }
  if (in.bad()) throw InputError(std::string("cannot read ") + what + " '" + path + "'");
  return text;
}

}  // namespace hpcplan::env
