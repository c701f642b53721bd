# The `stocs` command-line tool. Under catkin it lands in devel/lib/stocs_ros/ (rosrun stocs_ros stocs).
file(GLOB STOCS_TOOL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tools/*.cpp)
add_executable(stocs ${STOCS_TOOL_SOURCES})
target_link_libraries(stocs PRIVATE stocs_core stocs_methods CLI11::CLI11 opencv_imgproc opencv_imgcodecs)
if(TARGET stocs_methods_open3d)
  target_link_libraries(stocs PRIVATE stocs_methods_open3d)
endif()
add_dependencies(stocs stocs_mesh_reader)  # reads assimp's formats (src/io/child_reader.h)

if(STOCS_CATKIN)
  install(TARGETS stocs RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
