#pragma once
// The envelope every hpcplan checkpoint shares (the fluid's, the simulator's), and the byte
// writer and reader their payloads are made with.
//
// A file: a magic line naming its kind, the format number of that kind, the hpcplan version
// that wrote it, the payload's size, the payload (little-endian, as the machines hpcplan runs
// on), and a 64-bit checksum of the payload (FNV-1a: it tells a damaged file from a sound one;
// it is not a security measure). A file of another kind, format or version, cut short, with
// bytes after its end or failing its checksum is an InputError "--restart 'FILE': <what>".
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace hpcplan::checkpoint {

// The version written into checkpoints (a checkpoint of another is refused).
std::string_view version();

// Appends trivially copyable values, arrays and strings to a byte string.
class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put_array(std::span<const T> a) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(a.size());
    if (!a.empty()) out_.append(reinterpret_cast<const char*>(a.data()), a.size() * sizeof(T));
  }
  template <class T>
  void put_array(const std::vector<T>& a) {
    put_array(std::span<const T>(a));
  }
  void put_string(std::string_view s) {
    put<std::uint64_t>(s.size());
    out_.append(s);
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

// Reads what a Writer wrote; every read past the end, and fail(), throws the InputError
// "--restart 'NAME': <what>".
class Reader {
 public:
  Reader(std::string_view in, const std::string& name) : in_(in), name_(name) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  // An array that must hold `expected` entries.
  template <class T>
  void get_array(std::vector<T>& a, std::uint64_t expected) {
    const auto n = get<std::uint64_t>();
    if (n != expected)
      fail("holds " + std::to_string(n) + " entries where " + std::to_string(expected) +
           " were expected");
    a.resize(n);
    if (n > 0) std::memcpy(a.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  // An array into memory of its size (the count saved must be out.size()).
  template <class T>
  void get_array(std::span<T> out) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = get<std::uint64_t>();
    if (n != out.size())
      fail("holds " + std::to_string(n) + " entries where " + std::to_string(out.size()) +
           " were expected");
    if (n > 0) std::memcpy(out.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  // An array of any length the bytes left can hold.
  template <class T>
  void get_array(std::vector<T>& a) {
    const auto n = get<std::uint64_t>();
    if (n > left() / sizeof(T)) fail("is cut short (a damaged or incomplete checkpoint)");
    a.resize(n);
    if (n > 0) std::memcpy(a.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  std::string get_string();
  std::size_t left() const { return in_.size() - at_; }
  [[noreturn]] void fail(const std::string& what) const;

 private:
  const char* take(std::uint64_t n);
  std::string_view in_;
  std::size_t at_ = 0;
  const std::string& name_;
};

// The file's bytes: the envelope around `payload`.
std::string seal(std::string_view magic, std::uint32_t format, std::string_view payload);

// The payload of a sealed file read from `name` (for messages), after every envelope check;
// `kind` names the magic's kind in the message of a foreign file ("an hpcplan fluid
// checkpoint").
std::string_view open(std::string_view bytes, std::string_view magic, std::uint32_t format,
                      std::string_view kind, const std::string& name);

// A checkpoint file's bytes. Only a regular file (a device or a pipe such as /dev/zero or a
// FIFO would be read without end), and its first bytes must be `magic` before the rest is
// read (a large file of another kind costs nothing): InputError "--restart 'PATH': ..."
// otherwise, `kind` naming what it is not.
std::string read_regular_file(const std::string& path, std::string_view magic,
                              std::string_view kind);

}  // namespace hpcplan::checkpoint
