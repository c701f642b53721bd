# The `stocs` command-line tool. Under catkin it lands in devel/lib/stocs_ros/ (rosrun stocs_ros stocs).
# src/tools/ holds the commands: one *_command.cpp per subcommand, stocs_main.cpp that registers
# them, the options they share. src/tools/report/ holds the reporting they use, a library of its
# own so that a command reads as what it does: markdown and CSV tables, PNG line plots, the metric,
# confidence and coverage columns, `stocs bench`'s report, the per-object run records, pose overlay
# images, the child process runner and the progress line. Commands include it as "report/<file>.h".

# Only the tool links it: static, not installed.
file(GLOB STOCS_TOOL_REPORT_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tools/report/*.cpp)
add_library(stocs_tool_report STATIC ${STOCS_TOOL_REPORT_SOURCES})
target_include_directories(stocs_tool_report PUBLIC ${PROJECT_SOURCE_DIR}/src/tools)
target_link_libraries(stocs_tool_report PUBLIC stocs_core PRIVATE fmt::fmt opencv_imgproc)

file(GLOB STOCS_TOOL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tools/*.cpp)
add_executable(stocs ${STOCS_TOOL_SOURCES})
target_link_libraries(stocs PRIVATE stocs_tool_report stocs_core stocs_methods CLI11::CLI11
  opencv_imgproc opencv_imgcodecs)
if(TARGET stocs_methods_open3d)
  target_link_libraries(stocs PRIVATE stocs_methods_open3d)
endif()
add_dependencies(stocs stocs_mesh_reader)  # reads assimp's formats (src/io/child_reader.h)

if(STOCS_CATKIN)
  install(TARGETS stocs RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
