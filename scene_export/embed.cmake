# Writes the bytes of INPUT as a C array NAME into OUTPUT:
#   cmake -DINPUT=... -DOUTPUT=... -DNAME=... -P embed.cmake
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" n)
math(EXPR size "${n} / 2")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," body "${hex}")
string(REGEX REPLACE "((0x..,){16})" "\\1\n  " body "${body}")
file(WRITE "${OUTPUT}"
  "/* Generated from ${INPUT} by embed.cmake; do not edit. */\n"
  "const unsigned char ${NAME}[] = {\n  ${body}0x00};\n"
  "const unsigned long ${NAME}_size = ${size}UL;\n")
