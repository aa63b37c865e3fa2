// A rank's share of the scene travels from the reader (rank 0) as one byte buffer: plain values,
// arrays of plain values and strings, read back in the order they were written. PETSc-free.
#pragma once
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace etfe {

class ByteWriter {
public:
  template <class T> void Put(const T &v) {
    static_assert(std::is_trivially_copyable<T>::value, "only plain values travel as bytes");
    const char *p = reinterpret_cast<const char *>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <class T> void Put(const std::vector<T> &v) {
    static_assert(std::is_trivially_copyable<T>::value, "only plain values travel as bytes");
    Put((unsigned long long)v.size());
    const char *p = reinterpret_cast<const char *>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
  }
  void Put(const std::string &s) { Put(std::vector<char>(s.begin(), s.end())); }
  std::vector<char> bytes;
};

// Reads what a ByteWriter wrote; a read past the end leaves ok false (and the value zero).
class ByteReader {
public:
  ByteReader() = default;
  explicit ByteReader(std::vector<char> b) : bytes_(std::move(b)) {}
  template <class T> void Get(T *v) {
    static_assert(std::is_trivially_copyable<T>::value, "only plain values travel as bytes");
    if (!Take(v, sizeof(T))) *v = T();
  }
  template <class T> void Get(std::vector<T> *v) {
    unsigned long long n = 0;
    Get(&n);
    if (!ok || n > (bytes_.size() - pos_) / (sizeof(T) ? sizeof(T) : 1)) {
      ok = false;
      v->clear();
      return;
    }
    v->resize(n);
    Take(v->data(), n * sizeof(T));
  }
  void Get(std::string *s) {
    std::vector<char> c;
    Get(&c);
    s->assign(c.begin(), c.end());
  }
  bool AtEnd() const { return pos_ == bytes_.size(); }
  bool ok = true;

private:
  bool Take(void *dst, size_t n) {
    if (!ok || n > bytes_.size() - pos_) return ok = false;
    if (n) std::memcpy(dst, bytes_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  std::vector<char> bytes_;
  size_t pos_ = 0;
};

} // namespace etfe
