# SPDX-License-Identifier: BSD-3-Clause
# quad::warnings: the warning set for quad's own code, linked PRIVATE by every target.
# Generated code (fastddsgen) does not link it: it is not clean under -Wconversion.
add_library(quad_warnings INTERFACE)
add_library(quad::warnings ALIAS quad_warnings)
target_compile_options(quad_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Wunused -Woverloaded-virtual -Wconversion -Wsign-conversion
  -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough
  # Designated initializers leave members at their defaults on purpose.
  -Wno-missing-field-initializers)
if(QUAD_WERROR)
  target_compile_options(quad_warnings INTERFACE -Werror)
endif()
