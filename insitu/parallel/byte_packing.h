// insitu/parallel/byte_packing.h - values as bytes for a message between ranks, and back: the
// same machine's layout on every rank (one job runs one build on one kind of node). Read back
// by copying, so that nothing depends on where a value falls in the buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "voxspan/error.h"

namespace voxspan {

class Packer {
 public:
  template <class T> void put(const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof v);
  }
  // The values as they are; the reader must know how many.
  template <class T> void put_span(std::span<const T> v) {
    if (v.empty()) return;  // data() may be null, and no offset may be added to null
    const auto* p = reinterpret_cast<const std::byte*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size_bytes());
  }
  // Their count, then the values.
  template <class T> void put_all(std::span<const T> v) {
    put(std::uint64_t(v.size()));
    put_span(v);
  }
  std::vector<std::byte> bytes;
};

class Unpacker {
 public:
  // `what` names the message in the error a short one throws ("a rank's snapshot copy").
  Unpacker(std::span<const std::byte> bytes, std::string what)
      : bytes_(bytes), what_(std::move(what)) {}
  bool done() const { return at_ == bytes_.size(); }
  template <class T> T get() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  // n values appended to `out`.
  template <class T> void get_span(std::size_t n, std::vector<T>& out) {
    const std::size_t first = out.size();
    out.resize(first + n);
    take(out.data() + first, n * sizeof(T));
  }
  // What put_all wrote, into `out`.
  template <class T> void get_all(std::vector<T>& out) {
    out.clear();
    get_span(std::size_t(get<std::uint64_t>()), out);
  }

 private:
  void take(void* out, std::size_t n) {
    if (bytes_.size() - at_ < n) throw make_error(what_, " is cut short");
    if (n == 0) return;  // `out` may be an empty vector's null data(), which memcpy may not take
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }
  std::span<const std::byte> bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace voxspan
