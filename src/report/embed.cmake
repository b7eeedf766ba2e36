# Writes OUT: a C file defining the char array NAME, NUL-terminated, with
# the bytes of IN, so that the page's script and style sheet stay files
# of their own (page.js, page.css) yet live in the library.
file(READ "${IN}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
file(WRITE "${OUT}" "/* generated from ${NAME_OF_IN} by embed.cmake */\n"
  "extern const char ${NAME}[];\nconst char ${NAME}[] = {\n${bytes}0x00};\n")
