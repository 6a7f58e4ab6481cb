# SPDX-License-Identifier: BSD-3-Clause
# Finds every third-party dependency. Each comes from a Debian 12 package; when one is
# missing, configure stops with the package to install instead of a CMake search trace.

function(quad_require package debian_package)
  find_package(${package} ${ARGN} QUIET)
  if(NOT ${package}_FOUND)
    message(FATAL_ERROR
      "quad: dependency '${package}' not found. Install the Debian package: "
      "apt-get install ${debian_package}")
  endif()
endfunction()

function(quad_require_program variable program debian_package)
  find_program(${variable} ${program})
  if(NOT ${variable})
    message(FATAL_ERROR
      "quad: program '${program}' not found. Install the Debian package: "
      "apt-get install ${debian_package}")
  endif()
endfunction()

quad_require(fastcdr libfastcdr-dev)
quad_require(fastrtps libfastrtps-dev)
quad_require_program(QUAD_FASTDDSGEN fastddsgen fastddsgen)
quad_require_program(QUAD_FASTDDS_TOOL fastdds fastdds-tools)
quad_require(Eigen3 libeigen3-dev 3.4 NO_MODULE)
quad_require(octomap liboctomap-dev)
quad_require(mrpt-poses libmrpt-poses-dev)
quad_require(mrpt-math libmrpt-math-dev)
quad_require(fmt libfmt-dev)
quad_require(spdlog libspdlog-dev)
quad_require(yaml-cpp libyaml-cpp-dev)
quad_require(CLI11 libcli11-dev)
quad_require(nlohmann_json nlohmann-json3-dev)
quad_require(zstd libzstd-dev)
quad_require(OpenSSL libssl-dev)
quad_require(Boost libboost-dev 1.74 CONFIG)  # Boost.Beast (header-only): quad bridge's WebSockets
find_package(Threads REQUIRED)
if(QUAD_BUILD_TESTS)
  quad_require(GTest libgtest-dev)
endif()
if(QUAD_BUILD_BENCHMARKS)
  quad_require(benchmark libbenchmark-dev)
endif()
