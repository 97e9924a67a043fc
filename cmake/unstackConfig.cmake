# unstack's CMake package (docs/install.md): find_package(unstack) gives the
# imported target unstack::unstack, the shared library libunstack.so with
# the include directory of <unstack/unstack.h>. The library's own
# dependencies are linked into it or loaded as modules, so none is needed here.
include(${CMAKE_CURRENT_LIST_DIR}/unstackTargets.cmake)
