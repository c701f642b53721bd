# ROS 1 wrappers (catkin only): messages and services, the catkin package, the stocs_ros library of
# thin wrappers around the core, the stocs_node and scene_publisher executables and the nodelet.
# Included before the core targets because catkin_package() must precede every target.
# The ROS packages the wrappers build against and export; sorted, as catkin_lint asks.
set(STOCS_ROS_CATKIN_DEPENDS
  cv_bridge diagnostic_msgs dynamic_reconfigure geometry_msgs image_transport nodelet pluginlib
  roscpp roslib sensor_msgs std_msgs std_srvs tf2 tf2_eigen tf2_ros visualization_msgs)
set(STOCS_ROS_BUILD_COMPONENTS ${STOCS_ROS_CATKIN_DEPENDS} message_generation)
set(STOCS_ROS_EXPORTED_DEPENDS ${STOCS_ROS_CATKIN_DEPENDS} message_runtime)
list(SORT STOCS_ROS_BUILD_COMPONENTS)
list(SORT STOCS_ROS_EXPORTED_DEPENDS)
find_package(catkin REQUIRED COMPONENTS ${STOCS_ROS_BUILD_COMPONENTS})

add_message_files(DIRECTORY msg FILES Detection2D.msg Detection2DArray.msg InstanceMask.msg
  InstanceMaskArray.msg ObjectPose.msg ObjectPoseArray.msg RejectedObject.msg)
add_service_files(DIRECTORY srv FILES Estimate.srv)
generate_messages(DEPENDENCIES geometry_msgs sensor_msgs std_msgs)

catkin_package(
  INCLUDE_DIRS include
  LIBRARIES stocs_estimation stocs_eval stocs_geometry stocs_io stocs_methods stocs_model stocs_ros
            stocs_segmentation stocs_sim stocs_tracking stocs_util
  CATKIN_DEPENDS ${STOCS_ROS_EXPORTED_DEPENDS}
)

# The wrappers, a folder per program under src/ros/ (include/stocs_ros/ for their headers):
# common/ is what the programs share (conversions, the node's configuration, markers, the
# synchronizer), the library stocs_ros; each program folder is a static library of its own beside
# its executable's main (<folder>_main.cpp) and nodelet shell (*_nodelet.cpp).
function(stocs_ros_sources out folder)
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/ros/${folder}/*.cpp)
  list(FILTER sources EXCLUDE REGEX "(_main|_nodelet)\\.cpp$")
  set(${out} ${sources} PARENT_SCOPE)
endfunction()

stocs_ros_sources(STOCS_ROS_COMMON_SOURCES common)
add_library(stocs_ros ${STOCS_ROS_COMMON_SOURCES})
# The generated message headers (devel/include) reach every target through generate_messages().
target_include_directories(stocs_ros PUBLIC ${PROJECT_SOURCE_DIR}/include)
# PUBLIC: the node, nodelet and tests include ROS headers through the wrappers' headers. The package
# exports no CMake targets (catkin_package passes include folders by name), so no fixed path leaves it.
#catkin_lint: ignore_once EXTERNAL_INTERFACE_PATH
target_include_directories(stocs_ros SYSTEM PUBLIC ${catkin_INCLUDE_DIRS})
target_link_libraries(stocs_ros PUBLIC stocs_core ${catkin_LIBRARIES}
  PRIVATE yaml-cpp opencv_imgcodecs)
add_dependencies(stocs_ros ${PROJECT_NAME}_generate_messages_cpp ${catkin_EXPORTED_TARGETS})

# stocs_ros_program_library(FOLDER [deps...]): the static library stocs_ros_FOLDER of src/ros/FOLDER
# (without its main and nodelet shell), on stocs_ros.
function(stocs_ros_program_library folder)
  stocs_ros_sources(sources ${folder})
  add_library(stocs_ros_${folder} STATIC ${sources})
  set_target_properties(stocs_ros_${folder} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_link_libraries(stocs_ros_${folder} PUBLIC stocs_ros ${ARGN})
endfunction()
stocs_ros_program_library(stocs_node)
stocs_ros_program_library(scene_publisher)
stocs_ros_program_library(segmentation_node)
stocs_ros_program_library(demo_recorder)
stocs_ros_program_library(config_reference stocs_ros_segmentation_node stocs_ros_scene_publisher
  stocs_ros_demo_recorder stocs_ros_stocs_node)

# The executables, each its folder's main on its folder's library (spelled out for catkin_lint).
add_executable(stocs_node ${PROJECT_SOURCE_DIR}/src/ros/stocs_node/stocs_node_main.cpp)
target_link_libraries(stocs_node PRIVATE stocs_ros_stocs_node)
add_executable(scene_publisher ${PROJECT_SOURCE_DIR}/src/ros/scene_publisher/scene_publisher_main.cpp)
target_link_libraries(scene_publisher PRIVATE stocs_ros_scene_publisher)
add_executable(segmentation_node
  ${PROJECT_SOURCE_DIR}/src/ros/segmentation_node/segmentation_node_main.cpp)
target_link_libraries(segmentation_node PRIVATE stocs_ros_segmentation_node)
add_executable(demo_recorder ${PROJECT_SOURCE_DIR}/src/ros/demo_recorder/demo_recorder_main.cpp)
target_link_libraries(demo_recorder PRIVATE stocs_ros_demo_recorder)
add_executable(config_reference
  ${PROJECT_SOURCE_DIR}/src/ros/config_reference/config_reference_main.cpp)
target_link_libraries(config_reference PRIVATE stocs_ros_config_reference)

# One plugin library holds the three nodelets (nodelet_plugins.xml).
file(GLOB STOCS_ROS_NODELET_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/ros/*/*_nodelet.cpp)
add_library(stocs_ros_nodelet ${STOCS_ROS_NODELET_SOURCES})
target_link_libraries(stocs_ros_nodelet PRIVATE stocs_ros_stocs_node stocs_ros_scene_publisher
  stocs_ros_segmentation_node)

install(TARGETS stocs_ros stocs_ros_nodelet
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(TARGETS config_reference demo_recorder scene_publisher segmentation_node stocs_node RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY include/stocs_ros/ DESTINATION ${CATKIN_PACKAGE_INCLUDE_DESTINATION})
install(DIRECTORY config launch meshes models DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(FILES nodelet_plugins.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
