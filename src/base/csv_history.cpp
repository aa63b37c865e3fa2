// Per-increment CSV histories (see csv_history.h).
#include "etfe/base/csv_history.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

namespace etfe {

namespace {

// Keeps the header and the rows of steps below `step`; written to a temporary and renamed, so a
// kill in between leaves the old file.
bool DropRowsFrom(const std::string &path, long long step) {
  std::ifstream in(path);
  if (!in) return false;
  std::vector<std::string> keep;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (in.eof()) break;  // no newline after it: a row torn by a kill or a full disk
    if (header) {
      keep.push_back(line);
      header = false;
      continue;
    }
    char *end = nullptr;
    const long long s = std::strtoll(line.c_str(), &end, 10);
    if (end != line.c_str() && s < step) keep.push_back(line);
  }
  in.close();
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) return false;
    for (const std::string &l : keep) out << l << '\n';
    if (!out) return false;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  return !ec;
}

} // namespace

FILE *CsvHistoryOpen(const std::string &path, long long step, const char *header) {
  static std::set<std::string> continued;  // files this process has already written to
  std::error_code ec;
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  const bool fresh = step <= 1 || !std::filesystem::exists(path);
  if (!fresh && !continued.count(path) && !DropRowsFrom(path, step)) return nullptr;
  continued.insert(path);
  FILE *f = std::fopen(path.c_str(), fresh ? "w" : "a");
  if (f && fresh) std::fprintf(f, "%s\n", header);
  return f;
}

std::string CsvHistoryPath(const std::string &given, const std::string &results_stem, const char *suffix) {
  if (!given.empty()) return given;
  return results_stem.empty() ? std::string() : results_stem + suffix;
}

} // namespace etfe
