/* sh_version (shafts.h): the project version CMake passes in. */
#include "shafts.h"

#ifndef SH_VERSION_STRING
#error "SH_VERSION_STRING must be defined by the build (core/CMakeLists.txt)"
#endif

const char *sh_version(void) { return SH_VERSION_STRING; }
