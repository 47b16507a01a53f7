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

namespace hpcplan::world {

// Calls fn(line number, words) for every line that has words after comments are removed.
template <class Fn>
void for_each_directive(std::string_view text, Fn&& fn) {
  int number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++number;
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

inline std::string where(const std::string& name, int line) {
  return name + ":" + std::to_string(line) + ": ";
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
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(std::string("cannot read ") + what + " '" + path + "'");
  return s.str();
}

}  // namespace hpcplan::world
