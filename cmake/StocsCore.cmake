# The ROS-free core library.
file(GLOB STOCS_CORE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/core/*.cpp)
add_library(stocs_core ${STOCS_CORE_SOURCES})
target_include_directories(stocs_core
  PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  PRIVATE ${PROJECT_SOURCE_DIR}/src/core ${XXHASH_INCLUDE_DIR} ${NANOFLANN_INCLUDE_DIR})
target_include_directories(stocs_core SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
target_link_libraries(stocs_core
  PUBLIC Eigen3::Eigen opencv_core opencv_imgproc opencv_imgcodecs fmt::fmt
  PRIVATE nlohmann_json::nlohmann_json ${PCL_COMMON_LIBRARIES} ${PCL_IO_LIBRARIES}
          ${XXHASH_LIBRARY} OpenMP::OpenMP_CXX Threads::Threads)
target_compile_definitions(stocs_core PRIVATE ${PCL_DEFINITIONS})
set_target_properties(stocs_core PROPERTIES POSITION_INDEPENDENT_CODE ON)

if(STOCS_CATKIN)
  install(TARGETS stocs_core
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  install(DIRECTORY include/stocs/ DESTINATION ${CATKIN_GLOBAL_INCLUDE_DESTINATION}/stocs)
endif()
