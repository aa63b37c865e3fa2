// Options files (see options_files.h).
#include "options_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>

namespace etfe {

namespace {

namespace fs = std::filesystem;

bool IsKey(const std::string &t) {
  return t.size() > 1 && t[0] == '-' && !(std::isdigit((unsigned char)t[1]) || t[1] == '.');
}

// Whitespace-separated tokens; a double-quoted token keeps its spaces (without the quotes).
bool Tokenize(const std::string &line, std::vector<std::string> *tokens) {
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace((unsigned char)line[i])) ++i;
    if (i >= line.size()) break;
    std::string t;
    if (line[i] == '"') {
      const size_t end = line.find('"', i + 1);
      if (end == std::string::npos) return false;
      t = line.substr(i + 1, end - i - 1);
      i = end + 1;
    } else {
      while (i < line.size() && !std::isspace((unsigned char)line[i])) t += line[i++];
    }
    tokens->push_back(t);
  }
  return true;
}

// The product's own folder: the nearest folder above the running executable that holds options/
// (build/etfe -> the checkout), else the checkout it was built from, or empty.
fs::path ProductRoot() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  for (fs::path dir = exe.parent_path(); !ec && !dir.empty(); dir = dir.parent_path()) {
    if (fs::is_directory(dir / "options", ec)) return dir;
    if (dir == dir.root_path()) break;
  }
#ifdef ETFE_SOURCE_DIR
  if (fs::is_directory(fs::path(ETFE_SOURCE_DIR) / "options", ec)) return ETFE_SOURCE_DIR;
#endif
  return {};
}

// G named inside F: F's folder and each folder above it, then the working folder, then the
// product's folder and its options/ (so that a user's file anywhere can include the shipped
// "options/solvers/..." as the shipped cases do). Empty when none has it; *tried lists each path.
fs::path ResolveInclude(const fs::path &including, const std::string &name, std::vector<fs::path> *tried) {
  const fs::path g(name);
  std::error_code ec;
  if (g.is_absolute()) {
    tried->push_back(g);
    return fs::is_regular_file(g, ec) ? g : fs::path();
  }
  std::vector<fs::path> dirs;
  for (fs::path dir = fs::absolute(including).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    dirs.push_back(dir);
    if (dir == dir.root_path()) break;
  }
  dirs.push_back(fs::current_path(ec));
  const fs::path root = ProductRoot();
  if (!root.empty()) dirs.insert(dirs.end(), {root, root / "options"});
  for (const fs::path &dir : dirs) {
    const fs::path candidate = (dir / g).lexically_normal();
    if (std::find(tried->begin(), tried->end(), candidate) != tried->end()) continue;
    tried->push_back(candidate);
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  return {};
}

// "# requires: FILE from MAKER" (the form scripts/run reads), or false.
bool ParseRequirement(const std::string &line, const std::string &options_file, OptionsFileRequirement *r) {
  static const std::string lead = "# requires: ", from = " from ";
  if (line.compare(0, lead.size(), lead) != 0) return false;
  const size_t at = line.rfind(from);
  if (at == std::string::npos || at < lead.size()) return false;
  r->file = line.substr(lead.size(), at - lead.size());
  r->maker = line.substr(at + from.size());
  while (!r->maker.empty() && std::isspace((unsigned char)r->maker.back())) r->maker.pop_back();
  r->options_file = options_file;
  return !r->file.empty() && !r->maker.empty();
}

bool ExpandFile(const fs::path &file, std::vector<std::string> *out, std::set<std::string> *open, int depth,
                std::string *error, std::vector<OptionsFileRequirement> *requirements) {
  const std::string shown = file.string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    *error = "options file " + shown + ": no such file";
    return false;
  }
  if (depth > 16 || open->count(fs::canonical(file, ec).string())) {
    *error = "options file " + shown + ": includes itself (an -options_file loop)";
    return false;
  }
  open->insert(fs::canonical(file, ec).string());
  std::ifstream in(file);
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = shown + ":" + std::to_string(lineno);
    OptionsFileRequirement r;
    if (requirements && ParseRequirement(line, shown, &r)) requirements->push_back(r);
    const size_t hash = line.find_first_of("#!%");
    if (hash != std::string::npos) line.erase(hash);
    std::vector<std::string> tokens;
    if (!Tokenize(line, &tokens)) {
      *error = where + ": a quote is not closed";
      return false;
    }
    for (size_t k = 0; k < tokens.size(); ++k) {
      const std::string &t = tokens[k];
      if (!IsKey(t)) {
        *error = where + ": '" + t + "' is neither an option (-name) nor the value of one; write one " +
                 "\"-option value\" per line (comments start with #)";
        return false;
      }
      const bool has_value = k + 1 < tokens.size() && !IsKey(tokens[k + 1]);
      if (t == "-options_file") {
        if (!has_value) {
          *error = where + ": -options_file needs a file name";
          return false;
        }
        std::vector<fs::path> tried;
        const fs::path included = ResolveInclude(file, tokens[k + 1], &tried);
        if (included.empty()) {
          *error = where + ": -options_file " + tokens[k + 1] + ": no such file; looked for";
          for (size_t i = 0; i < tried.size(); ++i) *error += (i ? ", " : " ") + tried[i].string();
          return false;
        }
        if (!ExpandFile(included, out, open, depth + 1, error, requirements)) {
          *error = where + ": in -options_file " + tokens[k + 1] + ": " + *error;
          return false;
        }
        ++k;
        continue;
      }
      out->push_back(t);
      if (has_value) out->push_back(tokens[++k]);
    }
  }
  open->erase(fs::canonical(file, ec).string());
  return true;
}

} // namespace

bool ExpandOptionsFiles(const std::vector<std::string> &args, std::vector<std::string> *expanded,
                        std::string *error, std::vector<OptionsFileRequirement> *requirements) {
  expanded->clear();
  for (size_t k = 0; k < args.size(); ++k) {
    if (args[k] != "-options_file") {
      expanded->push_back(args[k]);
      continue;
    }
    if (k + 1 >= args.size()) {
      *error = "-options_file needs a file name";
      return false;
    }
    std::set<std::string> open;
    if (!ExpandFile(fs::path(args[++k]), expanded, &open, 0, error, requirements)) return false;
  }
  return true;
}

} // namespace etfe
