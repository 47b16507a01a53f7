#include "hpcplan/core/checkpoint_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "hpcplan/core/error.hpp"

namespace hpcplan::checkpoint {

namespace {

std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace

std::string_view version() {
  return HPCPLAN_VERSION_STRING;
}

std::string Reader::get_string() {
  const auto n = get<std::uint64_t>();
  return std::string(take(n), n);
}

void Reader::fail(const std::string& what) const {
  throw InputError("--restart '" + name_ + "': " + what);
}

const char* Reader::take(std::uint64_t n) {
  if (n > in_.size() - at_) fail("is cut short (a damaged or incomplete checkpoint)");
  const char* p = in_.data() + at_;
  at_ += n;
  return p;
}

std::string seal(std::string_view magic, std::uint32_t format, std::string_view payload) {
  Writer file;
  file.bytes().append(magic);
  file.put(format);
  file.put_string(version());
  file.put<std::uint64_t>(payload.size());
  file.bytes().append(payload);
  file.put(fnv1a(payload));
  return std::move(file.bytes());
}

std::string_view open(std::string_view bytes, std::string_view magic, std::uint32_t format,
                      std::string_view kind, const std::string& name) {
  Reader head(bytes, name);
  if (bytes.substr(0, magic.size()) != magic) head.fail("is not " + std::string(kind));
  Reader r(bytes.substr(magic.size()), name);
  const auto found = r.get<std::uint32_t>();
  if (found != format)
    r.fail("has checkpoint format " + std::to_string(found) + "; this hpcplan reads format " +
           std::to_string(format));
  const std::string written_by = r.get_string();
  for (const char c : written_by)
    if (c < ' ' || c > '~') r.fail("has a damaged header");
  if (written_by != version())
    r.fail("was written by hpcplan " + written_by + "; this is hpcplan " + std::string(version()));
  const auto size = r.get<std::uint64_t>();
  if (size > r.left() || r.left() - size < sizeof(std::uint64_t))
    r.fail("is cut short (a damaged or incomplete checkpoint)");
  if (r.left() - size > sizeof(std::uint64_t)) r.fail("has bytes after its end (damaged)");
  const std::string_view payload = bytes.substr(bytes.size() - r.left(), size);
  std::uint64_t stored = 0;
  std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
  if (stored != fnv1a(payload)) r.fail("fails its checksum (a damaged checkpoint)");
  return payload;
}

std::string read_regular_file(const std::string& path, std::string_view magic,
                              std::string_view kind) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("--restart '" + path + "': is not a readable regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw InputError("--restart '" + path + "': cannot be read");
  // The magic line first: another file, however large, is refused without reading it.
  std::string bytes(std::min<std::uintmax_t>(size, magic.size()), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in || bytes != magic)
    throw InputError("--restart '" + path + "': is not " + std::string(kind));
  bytes.resize(size);  // (std::bad_alloc for a file larger than memory: a run failure)
  in.read(bytes.data() + magic.size(), static_cast<std::streamsize>(size - magic.size()));
  if (in.gcount() != static_cast<std::streamsize>(size - magic.size()))
    throw InputError("--restart '" + path + "': cannot be read");
  return bytes;
}

}  // namespace hpcplan::checkpoint
