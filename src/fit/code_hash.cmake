# The digest of the code that makes a fitted model, for the fit cache's key
# (model_key.c): the build line (compiler, flags) and every source file
# listed in LIST (its first line is the build line), each by its path
# under ROOT and its SHA-256. Writes OUT, a header defining NAME
# (FM_FIT_CODE when not given) as the digest, described by WHAT.
# usage: cmake -DLIST=FILE -DROOT=DIR -DOUT=HEADER [-DNAME=MACRO -DWHAT=TEXT]
#        -P code_hash.cmake
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
if(NOT NAME)
  set(NAME FM_FIT_CODE)
  set(WHAT "core, repair and fit")
endif()
file(WRITE "${OUT}"
  "/* Made by src/fit/code_hash.cmake: the digest of the sources of ${WHAT}\n"
  " * and of the compiler and flags they are built with. */\n"
  "#define ${NAME} \"${digest}\"\n")
