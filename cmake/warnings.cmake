# Warnings live in an interface target so that they stay scoped to drapelab's own code.
add_library(drape_warnings INTERFACE)
add_library(drape::warnings ALIAS drape_warnings)
target_compile_options(drape_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor>)
