# Build step: every "-name" string literal in the solver's sources, one C string per line, into
# the file OUT. etfe uses the list to tell a typo (an option of this project's prefixes that no
# source names) from an option that exists but is not used by the chosen configuration; it is
# derived from the sources at every build, so it cannot drift from them.
file(GLOB_RECURSE sources ${SRC_DIR}/*.cpp ${SRC_DIR}/*.h)
set(names "")
foreach(f ${sources})
  file(STRINGS ${f} lines REGEX "\"-[a-z][a-z0-9_]*\"")
  foreach(l ${lines})
    string(REGEX MATCHALL "\"-[a-z][a-z0-9_]*\"" found "${l}")
    list(APPEND names ${found})
  endforeach()
endforeach()
list(REMOVE_DUPLICATES names)
list(SORT names)
string(REPLACE ";" ",\n" body "${names}")
file(WRITE ${OUT}.tmp "${body}\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUT}.tmp ${OUT})
