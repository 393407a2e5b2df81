/* The library's version, written once in configure.ac (via config.h). */
#include "config.h"

#include "msocl.h"

const char *msocl_version_string(void) { return PACKAGE_VERSION; }

int msocl_version(void) {
  return MSOCL_VERSION_MAJOR * 10000 + MSOCL_VERSION_MINOR * 100 +
         MSOCL_VERSION_PATCH;
}
