// FNV-1a over the bytes of values: the fingerprints a checkpoint keeps (checkpoint_compare.h), to
// which a physics term adds its own parameters (PhysicsTerm::Fingerprint).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace etfe {

// FNV-1a, 64 bit: fast, and any changed byte changes it (not a cryptographic hash; a checkpoint
// guards against accidents, not adversaries).
class Fnv64 {
public:
  Fnv64() = default;
  explicit Fnv64(std::uint64_t state) : h_(state) {} // goes on from a hash's Value()
  void Add(const void *data, size_t n) {
    const unsigned char *p = static_cast<const unsigned char *>(data);
    for (size_t i = 0; i < n; ++i)
      h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  void Add(const std::string &s) {
    Add(s.size());
    Add(s.data(), s.size());
  }
  template <class T> void Add(const T &value) { Add(&value, sizeof value); }
  template <class T> void Add(const std::vector<T> &v) {
    Add(v.size());
    if (!v.empty()) Add(v.data(), v.size() * sizeof(T));
  }
  std::uint64_t Value() const { return h_; }

private:
  std::uint64_t h_ = 14695981039346656037ull;
};

} // namespace etfe
