# Turns an OpenCL source file into C string-literal lines (one per line).
s/\\/\\\\/g
s/"/\\"/g
s/^/"/
s/$/\\n"/
