# Warnings live on an interface target linked PRIVATE by our own targets, so that
# consumers of the installed library never inherit them.
add_library(pagecache_warnings INTERFACE)
target_compile_options(pagecache_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Wimplicit-fallthrough
  -Werror=return-type)
