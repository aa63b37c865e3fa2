// Per-increment CSV histories beside the results (probe pairs, a scene's probes). A history is
// continued across a restart: the first row a process writes at step k > 1 first drops every row
// of step >= k, which a run killed after its last checkpoint had written, so no step appears
// twice.
#pragma once
#include <cstdio>
#include <string>

namespace etfe {

// Opens `path` to append the row of `step` (the first column of every row is the step number):
// at step <= 1, or when the file does not exist, it is created with `header` (one line, no
// newline). Returns nullptr when the file cannot be written.
FILE *CsvHistoryOpen(const std::string &path, long long step, const char *header);

// Where a scene's history goes: the path its option gave, else <results stem><suffix> beside the
// results; "" without either (a run without results writes none: it would overwrite another run's).
std::string CsvHistoryPath(const std::string &given, const std::string &results_stem, const char *suffix);

} // namespace etfe
