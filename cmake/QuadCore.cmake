# SPDX-License-Identifier: BSD-3-Clause
# quad_forbid_links(<target> REASON <text> PATTERNS <regex>...)
#
# Fails configure when <target> links a library whose name matches one of the patterns,
# directly or through one of quad's own libraries. The layering rules are written with it.
function(quad_forbid_links target)
  cmake_parse_arguments(ARG "" "REASON" "PATTERNS" ${ARGN})
  set(pending ${target})
  set(seen)
  while(pending)
    list(POP_FRONT pending current)
    if(current IN_LIST seen OR NOT TARGET ${current})
      continue()
    endif()
    list(APPEND seen ${current})
    get_target_property(aliased ${current} ALIASED_TARGET)
    if(aliased)
      list(APPEND pending ${aliased})
      continue()
    endif()
    get_target_property(type ${current} TYPE)
    set(libs)
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(direct ${current} LINK_LIBRARIES)
      if(direct)
        list(APPEND libs ${direct})
      endif()
    endif()
    get_target_property(interface ${current} INTERFACE_LINK_LIBRARIES)
    if(interface)
      list(APPEND libs ${interface})
    endif()
    foreach(lib IN LISTS libs)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" lib "${lib}")
      foreach(pattern IN LISTS ARG_PATTERNS)
        if(lib MATCHES "${pattern}")
          message(FATAL_ERROR "quad: ${target} links ${lib} (through ${current}); ${ARG_REASON}")
        endif()
      endforeach()
      if(lib MATCHES "^quad")
        list(APPEND pending ${lib})
      endif()
    endforeach()
  endwhile()
endfunction()

# quad_check_core(<target>)
#
# A module's core holds the algorithm and must build without the middleware (STYLE: the
# algorithm compiles without Fast DDS): it links neither Fast DDS, the generated message
# types nor quad::dds, and no module's node.
function(quad_check_core target)
  quad_forbid_links(${target} REASON "DDS belongs in the module's node/"
    PATTERNS "^fastrtps$" "^fastcdr$" "^quad(_|::)msgs$" "^quad(_|::)dds$")
  quad_forbid_links(${target} REASON "a core never links a node" PATTERNS "_node_lib$")
endfunction()

# quad_add_core_library(<module> SOURCES <files...> [PUBLIC <libs...>] [PRIVATE <libs...>])
#
# A module's core: target quad_<module> (alias quad::<module>) with headers in include/,
# quad's warnings, and the check above that it stays free of DDS.
function(quad_add_core_library module)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target quad_${module})
  add_library(${target} ${ARG_SOURCES})
  add_library(quad::${module} ALIAS ${target})
  target_include_directories(${target} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE} quad::warnings)
  quad_check_core(${target})
endfunction()
