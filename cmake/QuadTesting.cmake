# SPDX-License-Identifier: BSD-3-Clause
# quad_add_gtest(<target> MODULE <module> LABEL <unit|integration|fault|security>
#                SOURCES <files...> LIBS <targets...> [SERIAL])
#
# One GoogleTest executable; each test case becomes a CTest test named
# <label>.<module>.<Suite>.<Case> with the given label. SERIAL: each runs alone (a test whose
# processes need the whole machine, as the fault scenarios do).
function(quad_add_gtest target)
  cmake_parse_arguments(ARG "SERIAL" "MODULE;LABEL;TIMEOUT" "SOURCES;LIBS;ENVIRONMENT" ${ARGN})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main quad::warnings)
  gtest_discover_tests(${target}
    TEST_PREFIX "${ARG_LABEL}.${ARG_MODULE}."
    PROPERTIES LABELS ${ARG_LABEL} TIMEOUT ${ARG_TIMEOUT} RUN_SERIAL ${ARG_SERIAL} ENVIRONMENT "${ARG_ENVIRONMENT}"
    DISCOVERY_TIMEOUT 30)
endfunction()
