# Google Benchmark programs (speed is measured here, never in unit tests). Not run by the tests.
find_package(benchmark QUIET)
if(NOT benchmark_FOUND)
  message(STATUS "Google Benchmark not found: benchmarks are not built")
  return()
endif()
add_library(stocs_benchmark_frames STATIC ${PROJECT_SOURCE_DIR}/benchmark/benchmark_frames.cpp)
target_link_libraries(stocs_benchmark_frames PUBLIC stocs_core opencv_imgproc)
foreach(name stage scaling)
  add_executable(stocs_${name}_benchmarks ${PROJECT_SOURCE_DIR}/benchmark/${name}_benchmarks.cpp)
  target_link_libraries(stocs_${name}_benchmarks PRIVATE stocs_benchmark_frames benchmark::benchmark)
endforeach()
# The segmentation node's stages and the segmentation from depth alone
# (benchmark/segmentation_benchmarks.cpp).
add_executable(stocs_segmentation_benchmarks ${PROJECT_SOURCE_DIR}/benchmark/segmentation_benchmarks.cpp)
target_link_libraries(stocs_segmentation_benchmarks PRIVATE stocs_benchmark_frames benchmark::benchmark)
target_compile_definitions(stocs_segmentation_benchmarks PRIVATE
  STOCS_SEGMENTER_MODEL="${PROJECT_SOURCE_DIR}/models/segmenter.onnx")

if(STOCS_CATKIN)
  install(TARGETS stocs_scaling_benchmarks stocs_segmentation_benchmarks stocs_stage_benchmarks
    RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
