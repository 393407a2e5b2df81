# Turns an OpenCL source file into C string-literal lines (one per line),
# its own #include lines blank: the program holds every header already.
s/^#include ".*"$//
s/\\/\\\\/g
s/"/\\"/g
s/^/"/
s/$/\\n"/
