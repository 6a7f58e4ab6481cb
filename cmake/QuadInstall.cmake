# SPDX-License-Identifier: BSD-3-Clause
# `cmake --install <build> --prefix P`: a relocatable installation.
#   P/bin/quad                       the command
#   P/lib/quad/quad_<module>_node    the module programs, and quad_container, which hosts several
#   P/share/quad/{configs,bringup,idl}
# The programs find the rest from their own place (quad/common/layout.hpp), so the prefix can
# move. The folders are fixed (no lib64 or multiarch folder): layout.hpp looks for them so.
install(TARGETS quad RUNTIME DESTINATION bin)
install(TARGETS quad_plant_node quad_estimation_node quad_mapping_node quad_planning_node quad_control_node
  quad_display_node quad_container
  RUNTIME DESTINATION lib/quad)
install(DIRECTORY configs bringup DESTINATION share/quad)
install(DIRECTORY idl/ DESTINATION share/quad/idl FILES_MATCHING PATTERN "*.idl")
install(FILES LICENSE DESTINATION share/doc/quad)

# `cpack -G DEB` (in the build folder): a Debian package of the same installation under /usr.
# Its dependencies are the shared libraries the programs link, found by dpkg-shlibdeps.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME quad)
set(CPACK_PACKAGE_VENDOR "quad")
set(CPACK_PACKAGE_CONTACT "quad maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "DDS-based distributed flight stack: mapping, D* Lite planning, SO(3) control, simulation")
set(CPACK_PACKAGE_DESCRIPTION
  "quad flies a simulated quadcopter whose mapping (OctoMap), planning (D* Lite), control and
simulation run as separate Fast DDS participants, launched from one manifest on one machine
or several, with recording, replay and fault injection.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# ip and iptables for network-namespace hosts and the firewall, ssh for remote hosts,
# fastdds for a discovery server: used only by the manifests that ask for them.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "fastdds-tools, iproute2, iptables, openssh-client")
include(CPack)
