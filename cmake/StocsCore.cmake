# The ROS-free core: one library per module, each a folder of public headers
# (include/stocs/<module>/) and sources with their private headers (src/<module>/). Dependencies run
# one way:
#   util <- geometry <- io <- model <- estimation      (the algorithm and what it needs)
#   estimation <- tracking                              (poses followed from frame to frame)
#   geometry, io <- sim                                 (scene generator, segmentation simulator)
#   io, sim <- eval                                     (metrics and dataset evaluation)
#   geometry, io <- segmentation <- estimation, sim     (ONNX segmentation networks, OpenCV DNN;
#                                                        segmentation from depth alone, PCL)
# `stocs::core` is all of them, for programs that use every module (the tool, the tests).

# stocs_add_module(NAME [PUBLIC deps...] [PRIVATE deps...]): the library stocs_NAME (alias
# stocs::NAME) of src/NAME/**/*.cpp (sub-folders group a module's sources: one library still), or
# an interface library for a module of headers only.
function(stocs_add_module module)
  cmake_parse_arguments(M "" "" "PUBLIC;PRIVATE" ${ARGN})
  set(target stocs_${module})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${module}/*.cpp)
  if(sources)
    add_library(${target} ${sources})
    target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src/${module})
    target_link_libraries(${target} PUBLIC ${M_PUBLIC} PRIVATE ${M_PRIVATE})
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    set(scope PUBLIC)
  else()
    add_library(${target} INTERFACE)
    target_link_libraries(${target} INTERFACE ${M_PUBLIC})
    set(scope INTERFACE)
  endif()
  target_include_directories(${target} ${scope}
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${module})
  add_library(stocs::${module} ALIAS ${target})
  set_property(GLOBAL APPEND PROPERTY STOCS_CORE_MODULES ${target})
endfunction()

stocs_add_module(util PUBLIC Eigen3::Eigen fmt::fmt PRIVATE yaml-cpp)
stocs_add_module(geometry PUBLIC stocs_util opencv_core)
# knn_index.h, a public header, wraps nanoflann (header-only); the path is for the build tree only.
#catkin_lint: ignore_once EXTERNAL_INTERFACE_PATH
target_include_directories(stocs_geometry SYSTEM PUBLIC $<BUILD_INTERFACE:${NANOFLANN_INCLUDE_DIR}>)
stocs_add_module(io PUBLIC stocs_geometry
  PRIVATE opencv_imgproc opencv_imgcodecs nlohmann_json::nlohmann_json ${PCL_COMMON_LIBRARIES}
  ${PCL_IO_LIBRARIES}
  assimp::assimp)
target_include_directories(stocs_io SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
target_compile_definitions(stocs_io PRIVATE ${PCL_DEFINITIONS})
# The program stocs_io reads assimp's formats in (src/io/child_reader.h): beside the library, where
# the library looks for it (for a static core that is the programs' folder, the build's root).
add_executable(stocs_mesh_reader ${PROJECT_SOURCE_DIR}/src/mesh_reader/mesh_reader_main.cpp)
target_include_directories(stocs_mesh_reader PRIVATE ${PROJECT_SOURCE_DIR}/src/io)
target_link_libraries(stocs_mesh_reader PRIVATE stocs_io)
set_target_properties(stocs_mesh_reader PROPERTIES RUNTIME_OUTPUT_DIRECTORY $<TARGET_FILE_DIR:stocs_io>)
stocs_add_module(model PUBLIC stocs_geometry PRIVATE stocs_io ${XXHASH_LIBRARY})
target_include_directories(stocs_model PRIVATE ${XXHASH_INCLUDE_DIR})
stocs_add_module(estimation PUBLIC stocs_model stocs_segmentation PRIVATE OpenMP::OpenMP_CXX Threads::Threads)
stocs_add_module(tracking PUBLIC stocs_estimation PRIVATE OpenMP::OpenMP_CXX)
stocs_add_module(segmentation PUBLIC stocs_geometry opencv_core
  PRIVATE stocs_io opencv_dnn opencv_imgproc ${PCL_FEATURES_LIBRARIES} ${PCL_SEGMENTATION_LIBRARIES}
  ${PCL_SAMPLE_CONSENSUS_LIBRARIES})
target_include_directories(stocs_segmentation SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
target_compile_definitions(stocs_segmentation PRIVATE ${PCL_DEFINITIONS})
stocs_add_module(sim PUBLIC stocs_io
  PRIVATE stocs_segmentation opencv_imgproc opencv_imgcodecs nlohmann_json::nlohmann_json)
stocs_add_module(eval PUBLIC stocs_io stocs_sim)

add_library(stocs_core INTERFACE)
target_link_libraries(stocs_core INTERFACE
  stocs_util stocs_geometry stocs_io stocs_model stocs_estimation stocs_tracking stocs_sim
  stocs_eval stocs_segmentation)
set_target_properties(stocs_core PROPERTIES EXPORT_NAME core)
add_library(stocs::core ALIAS stocs_core)

get_property(modules GLOBAL PROPERTY STOCS_CORE_MODULES)
if(STOCS_CATKIN)
  install(TARGETS ${modules}
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  install(TARGETS stocs_mesh_reader RUNTIME DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  install(DIRECTORY include/stocs/ DESTINATION ${CATKIN_GLOBAL_INCLUDE_DESTINATION}/stocs)
endif()

# A plain CMake build installs the core for find_package(stocs) (examples/estimate_pose).
if(NOT STOCS_CATKIN)
  # A plain CMake build, never a catkin one: not linted.
  #catkin_lint: skip
  include(GNUInstallDirs)
  include(CMakePackageConfigHelpers)
  install(TARGETS ${modules} stocs_core EXPORT stocsTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(TARGETS stocs_mesh_reader RUNTIME DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/stocs/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stocs)
  set(STOCS_CONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/stocs)
  install(EXPORT stocsTargets NAMESPACE stocs:: DESTINATION ${STOCS_CONFIG_DIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/stocsConfig.cmake.in
    ${PROJECT_BINARY_DIR}/stocsConfig.cmake INSTALL_DESTINATION ${STOCS_CONFIG_DIR})
  install(FILES ${PROJECT_BINARY_DIR}/stocsConfig.cmake DESTINATION ${STOCS_CONFIG_DIR})
endif()
