add_library(graspmix_warnings INTERFACE)
target_compile_options(graspmix_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wno-unused-parameter>)
add_library(graspmix::warnings ALIAS graspmix_warnings)
