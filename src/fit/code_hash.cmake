# The digest of the code that makes a fitted model, for the fit cache's key
# (model_key.c): the build line (compiler, flags) and every source file
# listed in LIST (its first line is the build line), each by its path
# under ROOT and its SHA-256. Writes OUT, a header defining FM_FIT_CODE.
# usage: cmake -DLIST=FILE -DROOT=DIR -DOUT=HEADER -P code_hash.cmake
file(STRINGS "${LIST}" lines)
list(GET lines 0 build)
list(REMOVE_AT lines 0)
set(acc "${build}\n")
foreach(f IN LISTS lines)
  file(SHA256 "${f}" h)
  file(RELATIVE_PATH rel "${ROOT}" "${f}")
  string(APPEND acc "${rel} ${h}\n")
endforeach()
string(SHA256 digest "${acc}")
file(WRITE "${OUT}"
  "/* Made by src/fit/code_hash.cmake: the digest of the sources of core, repair\n"
  " * and fit and of the compiler and flags they are built with. */\n"
  "#define FM_FIT_CODE \"${digest}\"\n")
