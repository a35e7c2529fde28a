# cmake -DIN=file -DOUT=file.cpp -P EmbedText.cmake: writes `extern const char kPreludeSource[]`
# holding the text of IN as a raw string literal.
file(READ ${IN} text)
string(FIND "${text}" ")rigidlab\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw-string delimiter")
endif()
file(WRITE ${OUT} "// Generated from ${IN}. Do not edit.\nextern const char kPreludeSource[];\nconst char kPreludeSource[] = R\"rigidlab(${text})rigidlab\";\n")
