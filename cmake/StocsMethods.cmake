# Pose estimation methods behind one interface (StoCS, its ablations, baselines), kept out of the
# core so that heavy registration and surface-matching headers compile only here.
file(GLOB STOCS_METHOD_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/methods/*.cpp)
add_library(stocs_methods ${STOCS_METHOD_SOURCES})
target_link_libraries(stocs_methods PUBLIC stocs_core PRIVATE fmt::fmt)
set_target_properties(stocs_methods PROPERTIES POSITION_INDEPENDENT_CODE ON)

if(STOCS_CATKIN)
  install(TARGETS stocs_methods
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
endif()
