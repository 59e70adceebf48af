# SPDX-License-Identifier: BSD-3-Clause
# Compiler warnings for this project's C++, in the directory that includes this file and below:
# the standalone build (module, tests, examples, benchmarks) and the ParaView plugin. VTK's and
# other packages' headers come in as system headers and stay quiet; C sources (the reference
# mikktspace.c) keep their flags. Inside a VTK source tree VTK's own warning settings apply
# instead. The test command turns NORMALMAPPING_WARNINGS_AS_ERRORS on.
option(NORMALMAPPING_WARNINGS_AS_ERRORS "Treat compiler warnings in this project as errors" OFF)
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  add_compile_options(
    "$<$<COMPILE_LANGUAGE:CXX>:-Wall;-Wextra;-Wshadow;-Wnon-virtual-dtor;-Woverloaded-virtual>")
  if(NORMALMAPPING_WARNINGS_AS_ERRORS)
    add_compile_options("$<$<COMPILE_LANGUAGE:CXX>:-Werror>")
  endif()
endif()
