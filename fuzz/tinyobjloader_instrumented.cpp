// tinyobjloader's implementation, compiled into the OBJ fuzzer from the same header the system
// library (libtinyobjloader.so, the same Debian package) was built from. The executable's
// definitions take precedence over the shared library's, so the parser runs instrumented: libFuzzer
// sees its branches (coverage guides the search into the parser, not only into our wrapper) and
// ASan checks its memory accesses. A bug found here is a bug of the library collide_scene links.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
