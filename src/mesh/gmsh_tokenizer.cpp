// The tokenizer of the Gmsh MSH reader (see gmsh_tokenizer.h): the input is treated as hostile,
// so every number is parsed in full, every count is checked against the bytes left before
// anything is sized by it, and every failure becomes "<file>:<line>: <what>".
#include "gmsh_tokenizer.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace etfe {
namespace gmsh {

// Fuzzed or binary bytes can land in a message: keep it short and printable.
std::string Quote(std::string_view s) {
  std::string out = "'";
  const size_t n = std::min<size_t>(s.size(), 40);
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = (unsigned char)s[i];
    if (c >= 32 && c < 127) {
      out += (char)c;
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      out += b;
    }
  }
  if (s.size() > n) out += "...";
  return out + "'";
}

bool Input::FailAt(size_t pos, const std::string &msg) {
  if (!error_.empty()) return false;
  pos = std::min(pos, buf_.size());
  // Line numbers are counted only here: a parse that succeeds never pays for them.
  long long line = 1 + (long long)std::count(buf_.begin(), buf_.begin() + (long)pos, '\n');
  if (pos == buf_.size() && pos > 0 && buf_[pos - 1] == '\n') --line;  // EOF: the last line
  error_ = name_ + ":" + Str(line) + ": " + msg;
  if (binary_) error_ += " (binary data at byte offset " + Str((unsigned long long)pos) + ")";
  return false;
}

bool Input::Token(std::string_view *tok, const std::string &what) {
  SkipSpace();
  at_ = pos_;
  if (pos_ >= buf_.size()) return Fail("unexpected end of file, expected " + what);
  const size_t start = pos_;
  const size_t stop = std::min(buf_.size(), start + kMaxTokenChars + 1);
  while (pos_ < stop && !IsSpace(buf_[pos_])) ++pos_;
  *tok = std::string_view(buf_).substr(start, pos_ - start);
  if (pos_ - start > kMaxTokenChars) {
    return Fail("a token longer than " + Str((unsigned long long)kMaxTokenChars) + " characters (" +
                Quote(*tok) + "): not an ASCII MSH line; is the file damaged or not a mesh?");
  }
  if (pos_ - line_start_ > kMaxLineBytes) {
    return Fail("a line longer than " + Str((unsigned long long)kMaxLineBytes) +
                " bytes: not an ASCII MSH line; is the file damaged or not a mesh?");
  }
  return true;
}

bool Input::ReadInt(long long *v, const std::string &what, long long lo, long long hi) {
  if (binary_) {
    int32_t x = 0;
    if (!Raw(&x, sizeof x, what)) return false;
    *v = x;
  } else if (!IntToken(v, what)) {
    return false;
  }
  if (*v < lo || *v > hi) {
    return Fail(what + " " + Str(*v) + " is out of range (" + Str(lo) + ".." + Str(hi) + ")");
  }
  return true;
}

bool Input::ReadSize(unsigned long long *v, const std::string &what, unsigned long long lo,
                     unsigned long long hi) {
  if (binary_) {
    if (size_width_ == 4) {
      uint32_t x = 0;
      if (!Raw(&x, sizeof x, what)) return false;
      *v = x;
    } else {
      uint64_t x = 0;
      if (!Raw(&x, sizeof x, what)) return false;
      *v = x;
    }
  } else if (!IntToken(v, what)) {
    return false;
  }
  if (*v < lo || *v > hi) {
    return Fail(what + " " + Str(*v) + " is out of range (" + Str(lo) + ".." + Str(hi) + ")");
  }
  return true;
}

bool Input::ReadDouble(double *v, const std::string &what, bool finite) {
  if (binary_) {
    if (!Raw(v, sizeof *v, what)) return false;
  } else {
    std::string_view t;
    if (!Token(&t, what)) return false;
    const char *b = t.data(), *e = t.data() + t.size();
    if (e - b > 1 && *b == '+' && (b[1] == '.' || (b[1] >= '0' && b[1] <= '9'))) ++b;
    const auto r = std::from_chars(b, e, *v);
    if (r.ec == std::errc::result_out_of_range && r.ptr == e) {
      // Below the smallest denormal reads as zero (as strtod would); above the largest double
      // it is garbage.
      const size_t x = t.find_first_of("eE");
      if (x == std::string_view::npos || x + 1 >= t.size() || t[x + 1] != '-') {
        return Fail(what + " " + Quote(t) + " is out of the range of a double");
      }
      *v = (*b == '-') ? -0.0 : 0.0;
    } else if (r.ec != std::errc() || r.ptr != e) {
      return Fail("expected " + what + ", found " + Quote(t));
    }
  }
  if (finite && !std::isfinite(*v)) return Fail(what + " is not a finite number");
  return true;
}

bool Input::ReadCount(size_t *n, const std::string &what, size_t ascii_tokens,
                      size_t binary_bytes) {
  unsigned long long v;
  if (!ReadSize(&v, "number of " + what, 0, ULLONG_MAX)) return false;
  const size_t per_item = binary_ ? binary_bytes : 2 * ascii_tokens;
  if (per_item > 0 && v > Remaining() / per_item) {
    return Fail("number of " + what + " " + Str(v) + " is more than the remaining " +
                Str((unsigned long long)Remaining()) + " bytes of the file can hold");
  }
  *n = (size_t)v;
  return true;
}

bool Input::EndHeaderLine(const std::string &header) {
  while (pos_ < buf_.size() && (buf_[pos_] == ' ' || buf_[pos_] == '\t' || buf_[pos_] == '\r')) {
    ++pos_;
  }
  at_ = pos_;
  if (pos_ >= buf_.size() || buf_[pos_] != '\n') {
    return Fail("expected the end of the line after " + header);
  }
  ++pos_;
  return true;
}

bool Input::ExpectEnd(const std::string &section) {
  const std::string want = "$End" + section;
  std::string_view t;
  if (!Token(&t, want)) return false;
  if (t != want) {
    return Fail("expected " + want + ", found " + Quote(t) +
                " (do the counts in the section match its contents?)");
  }
  return true;
}

bool Input::SkipSection(std::string_view name, size_t header_pos) {
  const std::string needle = "\n$End" + std::string(name);
  size_t from = pos_;
  for (;;) {
    const size_t p = buf_.find(needle, from);
    if (p == std::string::npos) {
      return FailAt(header_pos, "section $" + std::string(name) + " has no $End" +
                                    std::string(name));
    }
    const size_t q = p + needle.size();
    if (q == buf_.size() || IsSpace(buf_[q])) {
      pos_ = q;
      return true;
    }
    from = p + 1;
  }
}

bool Input::QuotedName(std::string *name) {
  while (pos_ < buf_.size() && (buf_[pos_] == ' ' || buf_[pos_] == '\t')) ++pos_;
  at_ = pos_;
  if (pos_ >= buf_.size() || buf_[pos_] != '"') {
    return Fail("expected a physical name in double quotes");
  }
  const size_t start = ++pos_;
  const size_t stop = std::min(buf_.size(), start + kMaxTokenChars + 1);
  while (pos_ < stop && buf_[pos_] != '"' && buf_[pos_] != '\n') ++pos_;
  if (pos_ - start > kMaxTokenChars) {
    return Fail("physical name longer than " + Str((unsigned long long)kMaxTokenChars) +
                " characters");
  }
  if (pos_ >= buf_.size() || buf_[pos_] != '"') {
    return Fail("physical name has no closing double quote on its line");
  }
  *name = buf_.substr(start, pos_ - start);
  ++pos_;
  return true;
}

bool Input::Raw(void *out, size_t n, const std::string &what) {
  at_ = pos_;
  if (Remaining() < n) return Fail("unexpected end of file, expected " + what);
  unsigned char tmp[8];
  std::memcpy(tmp, buf_.data() + pos_, n);
  if (swap_) std::reverse(tmp, tmp + n);
  std::memcpy(out, tmp, n);
  pos_ += n;
  return true;
}

} // namespace gmsh
} // namespace etfe
