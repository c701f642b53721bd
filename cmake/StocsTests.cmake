# Unit and data tests. Under catkin they are catkin gtests (built by `make tests`, run by
# `catkin_make run_tests`); in a plain CMake build they are ctest tests. The data tests read the
# data folder from STOCS_DATASETS when they run, else from STOCS_DATASETS_DIR.

if(STOCS_CATKIN)
  if(NOT CATKIN_ENABLE_TESTING)
    return()
  endif()
else()
  include(CTest)
  if(NOT BUILD_TESTING)
    return()
  endif()
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()

# The tests' shared helpers, compiled once rather than into every test program: under the
# sanitizers every compilation of them is slow.
add_library(stocs_test_support STATIC ${PROJECT_SOURCE_DIR}/test/test_support.cpp)
target_include_directories(stocs_test_support PUBLIC ${PROJECT_SOURCE_DIR}/test)
target_link_libraries(stocs_test_support PUBLIC stocs_core GTest::gtest opencv_imgproc opencv_imgcodecs)
target_compile_definitions(stocs_test_support PRIVATE
  STOCS_DATASETS_DEFAULT="${STOCS_DATASETS_DIR}"
  STOCS_TEST_BINARY_DIR="${CMAKE_CURRENT_BINARY_DIR}")
if(STOCS_CATKIN)
  set_target_properties(stocs_test_support PROPERTIES EXCLUDE_FROM_ALL TRUE)  # built by `make tests`
endif()

# stocs_add_gtest(NAME SOURCES...): a gtest linked to the core and the methods.
function(stocs_add_gtest name)
  if(STOCS_CATKIN)
    catkin_add_gtest(${name} ${ARGN} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} GTest::gtest_main)  # catkin links gtest only
  else()
    add_executable(${name} ${ARGN})
    target_link_libraries(${name} GTest::gtest_main)
    gtest_discover_tests(${name} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
      DISCOVERY_TIMEOUT 60)
  endif()
  target_link_libraries(${name} stocs_test_support stocs_core stocs_methods)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/test)
  # The data folder and scratch folder are compiled into stocs_test_support; the CLI tests need the
  # tool's path.
  target_compile_definitions(${name} PRIVATE STOCS_TOOL_PATH="$<TARGET_FILE:stocs>")
  add_dependencies(${name} stocs)
endfunction()

# scripts/run_tests.sh turns this off in its catkin build: it runs these tests in its sanitizer
# build instead (building and running them in both would cost every CI run minutes).
# A core option, named as the others (see CMakeLists.txt).
#catkin_lint: ignore_once GLOBAL_VAR_COLLISION
option(STOCS_CORE_TESTS "Build the unit, CLI and real-data tests of the ROS-free core" ON)
if(STOCS_CORE_TESTS)
  file(GLOB STOCS_UNIT_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/unit/test_*.cpp)
  foreach(src ${STOCS_UNIT_TESTS})
    get_filename_component(name ${src} NAME_WE)
    stocs_add_gtest(${name} ${src})
  endforeach()
  if(TARGET stocs_methods_open3d AND TARGET test_baselines)
    target_link_libraries(test_baselines stocs_methods_open3d OpenMP::OpenMP_CXX)
  endif()
endif()
# test_mesh_formats and test_model_colour write format files with assimp's exporter.
foreach(name test_mesh_formats test_model_colour)
  if(TARGET ${name})
    target_link_libraries(${name} assimp::assimp)
  endif()
endforeach()
