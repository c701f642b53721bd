# Pose estimation methods behind one interface (StoCS, its ablations, baselines), kept out of the
# core so that heavy registration and surface-matching headers compile only here. Only this library
# links the baselines' components (found with the core's in CMakeLists.txt): PCL's 4PCS family
# (registration, with the kd-tree and search it queries and the plane model of its base selection)
# and OpenCV's PPF detector.

file(GLOB STOCS_METHOD_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/methods/*.cpp)
add_library(stocs_methods ${STOCS_METHOD_SOURCES})
target_include_directories(stocs_methods SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
target_link_libraries(stocs_methods PUBLIC stocs_core
  PRIVATE fmt::fmt opencv_surface_matching ${PCL_REGISTRATION_LIBRARIES} ${PCL_SEARCH_LIBRARIES}
          ${PCL_KDTREE_LIBRARIES} ${PCL_SAMPLE_CONSENSUS_LIBRARIES})
target_compile_definitions(stocs_methods PRIVATE ${PCL_DEFINITIONS})
set_target_properties(stocs_methods PROPERTIES POSITION_INDEPENDENT_CODE ON)

if(STOCS_CATKIN)
  install(TARGETS stocs_methods
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
endif()

# The Open3D baselines (src/methods/open3d, registered by open3d_methods.h), for benchmarks only:
# a library of their own, built where Open3D is found (CMakeLists.txt) and linked into the `stocs`
# tool and the baselines' test only, so that the core, the node and the ROS build never need it.
# Linking it defines STOCS_HAVE_OPEN3D.
if(Open3D_FOUND)
  file(GLOB STOCS_OPEN3D_METHOD_SOURCES CONFIGURE_DEPENDS
    ${PROJECT_SOURCE_DIR}/src/methods/open3d/*.cpp)
  add_library(stocs_methods_open3d ${STOCS_OPEN3D_METHOD_SOURCES})
  target_include_directories(stocs_methods_open3d PRIVATE ${PROJECT_SOURCE_DIR}/src/methods)
  target_link_libraries(stocs_methods_open3d PUBLIC stocs_methods
    PRIVATE Open3D::Open3D OpenMP::OpenMP_CXX)
  target_compile_definitions(stocs_methods_open3d PUBLIC STOCS_HAVE_OPEN3D)
  set_target_properties(stocs_methods_open3d PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(STOCS_CATKIN)
    install(TARGETS stocs_methods_open3d
      ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
      LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  endif()
else()
  message(STATUS "Open3D not found: the o3d-ransac and o3d-fgr baselines are not built")
endif()
