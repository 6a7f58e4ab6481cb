# `cmake --install <build> --prefix P`: a relocatable installation.
#   P/bin/quad                       the command
#   P/lib/quad/quad_<module>_node    the module programs
#   P/share/quad/{configs,bringup,idl}
# The programs find the rest from their own place (quad/common/layout.hpp), so the prefix can
# move. The folders are fixed (no lib64 or multiarch folder): layout.hpp looks for them so.
install(TARGETS quad RUNTIME DESTINATION bin)
install(TARGETS quad_plant_node quad_mapping_node quad_planning_node quad_control_node
  RUNTIME DESTINATION lib/quad)
install(DIRECTORY configs bringup DESTINATION share/quad)
install(DIRECTORY idl/ DESTINATION share/quad/idl FILES_MATCHING PATTERN "*.idl")
install(FILES LICENSE DESTINATION share/doc/quad)
