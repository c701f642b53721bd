# libFuzzer targets (fuzz/fuzz_*.cpp, one target each) for every parser of outside data. Needs
# clang with compiler-rt (Debian: clang, libclang-rt-14-dev). The core is instrumented for coverage
# and built with AddressSanitizer and UndefinedBehaviorSanitizer, so any memory error or UB in a
# parser stops the fuzzer with a report. Use a build folder of its own (scripts/fuzz.sh: build/fuzz).
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "STOCS_FUZZ needs clang (configure with -DCMAKE_CXX_COMPILER=clang++)")
endif()

set(STOCS_FUZZ_SANITIZERS address,undefined)
set(STOCS_FUZZ_COMPILE_FLAGS -fsanitize=fuzzer-no-link,${STOCS_FUZZ_SANITIZERS}
    -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
get_property(STOCS_FUZZ_MODULES GLOBAL PROPERTY STOCS_CORE_MODULES)
foreach(module ${STOCS_FUZZ_MODULES})
  get_target_property(type ${module} TYPE)
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    target_compile_options(${module} PRIVATE ${STOCS_FUZZ_COMPILE_FLAGS})
  endif()
endforeach()

# The ROS message conversion is compiled from src/ros directly against the ROS headers and
# libraries in /usr, so the fuzz build needs neither catkin nor the generated messages of this
# package (the conversion uses only sensor_msgs).
find_path(STOCS_FUZZ_SENSOR_MSGS_INCLUDE sensor_msgs/PointCloud2.h PATHS /usr/include)
find_path(STOCS_FUZZ_CV_BRIDGE_INCLUDE cv_bridge/cv_bridge.h PATHS /usr/include)
find_library(STOCS_FUZZ_CV_BRIDGE_LIB cv_bridge)
find_library(STOCS_FUZZ_ROSCPP_SERIALIZATION_LIB roscpp_serialization)
find_library(STOCS_FUZZ_ROSTIME_LIB rostime)
find_library(STOCS_FUZZ_CPP_COMMON_LIB cpp_common)
set(STOCS_FUZZ_ROS_FOUND FALSE)
if(STOCS_FUZZ_SENSOR_MSGS_INCLUDE AND STOCS_FUZZ_CV_BRIDGE_INCLUDE AND STOCS_FUZZ_CV_BRIDGE_LIB
   AND STOCS_FUZZ_ROSCPP_SERIALIZATION_LIB AND STOCS_FUZZ_ROSTIME_LIB AND STOCS_FUZZ_CPP_COMMON_LIB)
  set(STOCS_FUZZ_ROS_FOUND TRUE)
else()
  message(WARNING "ROS headers or libraries (sensor_msgs, cv_bridge) not found: no ROS fuzz targets")
endif()

# The seed corpus generator (a plain program: it writes fuzz/corpus/<target>/seed_* files).
add_executable(stocs_fuzz_make_corpus ${PROJECT_SOURCE_DIR}/fuzz/make_corpus.cpp)
target_link_libraries(stocs_fuzz_make_corpus stocs_core nlohmann_json::nlohmann_json opencv_imgcodecs)
target_compile_options(stocs_fuzz_make_corpus PRIVATE ${STOCS_FUZZ_COMPILE_FLAGS})
target_link_options(stocs_fuzz_make_corpus PRIVATE -fsanitize=${STOCS_FUZZ_SANITIZERS})

# The mesh reader fuzz_mesh_model starts for DAE files (src/io/child_reader.h), with the sanitizers.
target_compile_options(stocs_mesh_reader PRIVATE ${STOCS_FUZZ_COMPILE_FLAGS})
target_link_options(stocs_mesh_reader PRIVATE -fsanitize=${STOCS_FUZZ_SANITIZERS})

# The parsers are in these modules: the fuzz targets link them only, so the fuzz build compiles
# no more of the core (not the estimation, tracking, simulator, evaluation nor segmentation).
set(STOCS_FUZZ_LINKED_MODULES stocs_io stocs_model)
# The ROS message conversion, compiled once for both ROS fuzz targets.
if(STOCS_FUZZ_ROS_FOUND)
  add_library(stocs_fuzz_ros_conversion OBJECT ${PROJECT_SOURCE_DIR}/src/ros/common/cloud_conversion.cpp
              ${PROJECT_SOURCE_DIR}/src/ros/common/image_conversion.cpp)
  target_compile_options(stocs_fuzz_ros_conversion PRIVATE ${STOCS_FUZZ_COMPILE_FLAGS})
  target_include_directories(stocs_fuzz_ros_conversion SYSTEM PRIVATE
                             ${STOCS_FUZZ_SENSOR_MSGS_INCLUDE} ${STOCS_FUZZ_CV_BRIDGE_INCLUDE})
  target_link_libraries(stocs_fuzz_ros_conversion PRIVATE ${STOCS_FUZZ_LINKED_MODULES} fmt::fmt)
endif()

set(STOCS_FUZZ_TARGETS "")
file(GLOB STOCS_FUZZ_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/fuzz/fuzz_*.cpp)
foreach(src ${STOCS_FUZZ_SOURCES})
  get_filename_component(name ${src} NAME_WE)
  set(sources ${src})
  if(name MATCHES "^fuzz_ros_")
    if(NOT STOCS_FUZZ_ROS_FOUND)
      continue()
    endif()
    list(APPEND sources $<TARGET_OBJECTS:stocs_fuzz_ros_conversion>)
  endif()
  if(name STREQUAL "fuzz_lookalikes")  # the one parser of the simulator, without the rest of it
    list(APPEND sources ${PROJECT_SOURCE_DIR}/src/sim/lookalikes.cpp)
  endif()
  add_executable(${name} ${sources})
  target_compile_options(${name} PRIVATE -fsanitize=fuzzer,${STOCS_FUZZ_SANITIZERS}
                         -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(${name} PRIVATE -fsanitize=fuzzer,${STOCS_FUZZ_SANITIZERS})
  target_link_libraries(${name} ${STOCS_FUZZ_LINKED_MODULES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/fuzz)
  if(name STREQUAL "fuzz_mesh_model")  # calls the assimp reader in-process (src/io)
    target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/src/io)
  endif()
  if(name MATCHES "^fuzz_ros_")
    target_include_directories(${name} SYSTEM PRIVATE ${STOCS_FUZZ_SENSOR_MSGS_INCLUDE}
                               ${STOCS_FUZZ_CV_BRIDGE_INCLUDE})
    target_link_libraries(${name} fmt::fmt ${STOCS_FUZZ_CV_BRIDGE_LIB}
                          ${STOCS_FUZZ_ROSCPP_SERIALIZATION_LIB} ${STOCS_FUZZ_ROSTIME_LIB}
                          ${STOCS_FUZZ_CPP_COMMON_LIB})
  endif()
  list(APPEND STOCS_FUZZ_TARGETS ${name})
endforeach()
# `cmake --build build/fuzz --target fuzz` builds every fuzz target.
add_custom_target(fuzz DEPENDS ${STOCS_FUZZ_TARGETS} stocs_mesh_reader)
