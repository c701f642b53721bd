# Google Benchmark programs (speed is measured here, never in unit tests). Not run by the tests.
find_package(benchmark QUIET)
if(NOT benchmark_FOUND)
  message(STATUS "Google Benchmark not found: benchmarks are not built")
  return()
endif()
add_executable(stocs_stage_benchmarks ${PROJECT_SOURCE_DIR}/benchmark/stage_benchmarks.cpp)
target_link_libraries(stocs_stage_benchmarks PRIVATE stocs_core benchmark::benchmark)
