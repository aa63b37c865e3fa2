// Options files, read by etfe itself before PETSc starts: every "-options_file F" of the command
// line is replaced in place by F's options, so the precedence stays PETSc's (later wins: options
// after the file on the command line override it). An "-options_file G" line inside F names G
// relative to F's folder or, failing that, to the nearest folder above F where G exists (the
// repository root for the project's "options/solvers/..." includes), then to the working folder,
// then to the product's folder (the one above the executable holding options/) and its options/:
// a user's file anywhere includes the shipped solver files as the shipped cases do. A missing G
// names every path tried. A line that is not "-option [value]" stops with file:line and the reason.
#pragma once
#include <string>
#include <vector>

namespace etfe {

// A "# requires: FILE from MAKER" comment of an options file: the case reads FILE (a form-found
// surface), which the options file MAKER writes; scripts/run makes a missing one first. Kept so
// that an error about a missing FILE can say how to make it (error_handlers.h).
struct OptionsFileRequirement {
  std::string file, maker, options_file;
};

// args: argv[1..]; on success *expanded holds the new argument list (without argv[0]) and
// *requirements (if given) the "# requires:" comments of every options file read.
bool ExpandOptionsFiles(const std::vector<std::string> &args, std::vector<std::string> *expanded,
                        std::string *error, std::vector<OptionsFileRequirement> *requirements = nullptr);

} // namespace etfe
