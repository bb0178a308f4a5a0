# Writes the bytes of INPUT to OUTPUT as a C++ initializer list ("0x2f,0x2a,..."), to be
# #included in a byte array: the report's scripts and style sheet travel inside the library, so a
# report written anywhere holds everything it shows.
# Usage: cmake -DINPUT=file -DOUTPUT=file.inc -P EmbedBytes.cmake
file(READ "${INPUT}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
# Lines of 8 bytes, so that compilers and editors never meet one line of megabytes.
set(byte "0x[0-9a-f][0-9a-f],")
string(REGEX REPLACE "(${byte}${byte}${byte}${byte}${byte}${byte}${byte}${byte})" "\\1\n" bytes
       "${bytes}")
file(WRITE "${OUTPUT}.tmp" "${bytes}\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
