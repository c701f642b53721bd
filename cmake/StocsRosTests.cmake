# Tests of the ROS wrappers (catkin only): unit gtests that need no ROS master, the rostest
# integration tests (the node, the nodelet and the scene publisher together), and the launch file
# check. All run through `catkin_make run_tests`, as scripts/run_tests.sh does. Included only with
# CATKIN_ENABLE_TESTING.
find_package(rostest REQUIRED)
find_package(roslaunch REQUIRED)
roslaunch_add_file_check(launch)
# The wrappers the tests reach into: the shared library and every program's.
set(STOCS_ROS_TESTED_LIBRARIES stocs_ros_stocs_node stocs_ros_scene_publisher
  stocs_ros_segmentation_node stocs_ros_config_reference stocs_ros_demo_recorder)

file(GLOB STOCS_ROS_UNIT_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/ros/unit/test_*.cpp)
foreach(src ${STOCS_ROS_UNIT_TESTS})
  get_filename_component(name ${src} NAME_WE)
  stocs_add_gtest(ros_${name} ${src})
  target_link_libraries(ros_${name} ${STOCS_ROS_TESTED_LIBRARIES})
endforeach()

# The generated dataset and configs the integration tests play, written when the tests are built.
set(STOCS_ROS_TEST_DATA ${CMAKE_CURRENT_BINARY_DIR}/ros_test_data)
add_executable(stocs_ros_make_test_data EXCLUDE_FROM_ALL
  ${PROJECT_SOURCE_DIR}/test/ros/make_test_data.cpp ${PROJECT_SOURCE_DIR}/test/test_support.cpp)
target_include_directories(stocs_ros_make_test_data PRIVATE ${PROJECT_SOURCE_DIR}/test)
target_link_libraries(stocs_ros_make_test_data stocs_core GTest::gtest opencv_imgproc opencv_imgcodecs)
target_compile_definitions(stocs_ros_make_test_data PRIVATE
  STOCS_DATASETS_DEFAULT="" STOCS_TEST_BINARY_DIR="${CMAKE_CURRENT_BINARY_DIR}")
add_custom_command(OUTPUT ${STOCS_ROS_TEST_DATA}/synthetic.yaml
  COMMAND stocs_ros_make_test_data ${STOCS_ROS_TEST_DATA} ${PROJECT_SOURCE_DIR}/config/demo.yaml
  DEPENDS stocs_ros_make_test_data ${PROJECT_SOURCE_DIR}/config/demo.yaml
  COMMENT "Writing the generated dataset of the ROS tests")
# The demo's scene (scripts/demo.sh makes the same one), written by the CLI as a user would. After
# the writer above, which empties the whole folder first: side by side (make -j2) it would delete
# the scene's models/ while the CLI writes them.
add_custom_command(OUTPUT ${STOCS_ROS_TEST_DATA}/synth_scene/test/000000/scene_gt.json
  COMMAND ${CMAKE_COMMAND} -E remove_directory ${STOCS_ROS_TEST_DATA}/synth_scene
  COMMAND stocs synth --out ${STOCS_ROS_TEST_DATA}/synth_scene --objects 6 --distractors 2 --seed 1
    --quiet
  DEPENDS stocs ${STOCS_ROS_TEST_DATA}/synthetic.yaml
  COMMENT "Generating the cluttered scene of the ROS tests")
# A short sequence (24 frames at 320x240, every event a few frames long) for the scene publisher;
# after the writer above, which empties the whole folder first.
add_custom_command(OUTPUT ${STOCS_ROS_TEST_DATA}/sequence/test/000000/scene_events.json
  COMMAND ${CMAKE_COMMAND} -E remove_directory ${STOCS_ROS_TEST_DATA}/sequence
  COMMAND stocs synth --out ${STOCS_ROS_TEST_DATA}/sequence --sequence --frames 24 --objects 3
    --distractors 1 --width 320 --height 240 --fx 307.5 --fy 307.5 --cx 159.5 --cy 119.5
    --push-start 2 --push-frames 4 --lift-start 6 --lift-frames 4 --removal-start 10
    --removal-frames 6 --occlusion-start 17 --occlusion-frames 5 --seed 3 --quiet
  DEPENDS stocs ${STOCS_ROS_TEST_DATA}/synthetic.yaml
  COMMENT "Generating the sequence of the ROS tests")
# The textured scene (labelled box with its label toward the camera, printed can and mug, coloured
# models and rgb/); after the writer above, which empties the whole folder first.
add_custom_command(OUTPUT ${STOCS_ROS_TEST_DATA}/textured/test/000000/scene_gt.json
  COMMAND ${CMAKE_COMMAND} -E remove_directory ${STOCS_ROS_TEST_DATA}/textured
  COMMAND stocs synth --out ${STOCS_ROS_TEST_DATA}/textured --catalogue textured --objects 3
    --distractors 1 --seed 11 --quiet
  DEPENDS stocs ${STOCS_ROS_TEST_DATA}/synthetic.yaml
  COMMENT "Generating the textured scene of the ROS tests")
add_custom_target(stocs_ros_test_data DEPENDS ${STOCS_ROS_TEST_DATA}/synthetic.yaml
  ${STOCS_ROS_TEST_DATA}/synth_scene/test/000000/scene_gt.json
  ${STOCS_ROS_TEST_DATA}/sequence/test/000000/scene_events.json
  ${STOCS_ROS_TEST_DATA}/textured/test/000000/scene_gt.json)
add_dependencies(tests stocs_ros_test_data)

# stocs_add_rostest_node(NAME SOURCES...): a gtest executable that rostest launch files run.
function(stocs_add_rostest_node name)
  catkin_add_executable_with_gtest(${name} ${ARGN} ${PROJECT_SOURCE_DIR}/test/ros/ros_test_support.cpp
    ${PROJECT_SOURCE_DIR}/test/test_support.cpp EXCLUDE_FROM_ALL)
  add_dependencies(tests ${name})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/test ${PROJECT_SOURCE_DIR}/test/ros)
  target_link_libraries(${name} ${STOCS_ROS_TESTED_LIBRARIES})
  target_compile_definitions(${name} PRIVATE
    STOCS_DATASETS_DEFAULT="" STOCS_TEST_BINARY_DIR="${CMAKE_CURRENT_BINARY_DIR}"
    STOCS_NODE_PATH="$<TARGET_FILE:stocs_node>" SCENE_PUBLISHER_PATH="$<TARGET_FILE:scene_publisher>"
    SEGMENTATION_NODE_PATH="$<TARGET_FILE:segmentation_node>"
    SEGMENTER_MODEL="${PROJECT_SOURCE_DIR}/models/segmenter.onnx")
endfunction()
stocs_add_rostest_node(test_node_outputs ${PROJECT_SOURCE_DIR}/test/ros/test_node_outputs.cpp)
stocs_add_rostest_node(test_bad_inputs ${PROJECT_SOURCE_DIR}/test/ros/test_bad_inputs.cpp)
stocs_add_rostest_node(test_bad_config ${PROJECT_SOURCE_DIR}/test/ros/test_bad_config.cpp)
stocs_add_rostest_node(test_scene_poses ${PROJECT_SOURCE_DIR}/test/ros/test_scene_poses.cpp)
stocs_add_rostest_node(test_soak ${PROJECT_SOURCE_DIR}/test/ros/test_soak.cpp)
stocs_add_rostest_node(test_rejected_objects ${PROJECT_SOURCE_DIR}/test/ros/test_rejected_objects.cpp)
stocs_add_rostest_node(test_sequence_playback ${PROJECT_SOURCE_DIR}/test/ros/test_sequence_playback.cpp)
stocs_add_rostest_node(test_segmentation_node ${PROJECT_SOURCE_DIR}/test/ros/test_segmentation_node.cpp)
stocs_add_rostest_node(test_sequence_tracking ${PROJECT_SOURCE_DIR}/test/ros/test_sequence_tracking.cpp)
stocs_add_rostest_node(test_robot_frame ${PROJECT_SOURCE_DIR}/test/ros/test_robot_frame.cpp)

set(STOCS_ROS_TEST_DEPENDS stocs_node scene_publisher stocs_ros_nodelet stocs_ros_test_data)
add_rostest(test/ros/synthetic_playback.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_node_outputs ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/robot_frame.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_robot_frame ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/nodelet_multichannel.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_node_outputs ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/synth_scene_playback.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_scene_poses ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/textured_playback.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_scene_poses ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/segmentation_node.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_segmentation_node segmentation_node stocs_ros_test_data)
# The same checks on stocs_ros/SegmentationNodelet in a manager, and on the node's 8-bit maps.
add_rostest(test/ros/segmentation_node.test ARGS data:=${STOCS_ROS_TEST_DATA} nodelet:=true
  DEPENDENCIES test_segmentation_node stocs_ros_nodelet stocs_ros_test_data)
add_rostest(test/ros/segmentation_node.test ARGS data:=${STOCS_ROS_TEST_DATA} depth:=8U
  DEPENDENCIES test_segmentation_node segmentation_node stocs_ros_test_data)
# The same scene with maps from the package's segmentation network (segmentation_node).
add_rostest(test/ros/network_playback.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_scene_poses segmentation_node ${STOCS_ROS_TEST_DEPENDS})
foreach(form labels masks boxes)
  add_rostest(test/ros/segmentation_inputs.test ARGS data:=${STOCS_ROS_TEST_DATA} form:=${form}
    DEPENDENCIES test_scene_poses ${STOCS_ROS_TEST_DEPENDS})
endforeach()
# The same scene from depth alone (input.probability geometric).
add_rostest(test/ros/geometric_playback.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_scene_poses ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/rutgers_dove_instances.test DEPENDENCIES test_scene_poses ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/lmo_cat_playback.test DEPENDENCIES test_node_outputs ${STOCS_ROS_TEST_DEPENDS})
add_rostest(test/ros/bad_inputs.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_bad_inputs ${STOCS_ROS_TEST_DEPENDS})
foreach(config absent absent_detection)
  add_rostest(test/ros/absent_objects.test ARGS data:=${STOCS_ROS_TEST_DATA} config:=${config}
    DEPENDENCIES test_rejected_objects ${STOCS_ROS_TEST_DEPENDS})
endforeach()
add_rostest(test/ros/bad_config.test DEPENDENCIES test_bad_config stocs_node scene_publisher
  segmentation_node)
add_rostest(test/ros/sequence_playback.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_sequence_playback scene_publisher stocs_ros_test_data)
add_rostest(test/ros/sequence_tracking.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_sequence_tracking ${STOCS_ROS_TEST_DEPENDS})
# The short soak (25 s); the 5-minute run is documented in docs/reliability.md.
add_rostest(test/ros/soak.test ARGS data:=${STOCS_ROS_TEST_DATA}
  DEPENDENCIES test_soak ${STOCS_ROS_TEST_DEPENDS})

# The soak runs alone: `catkin_make -jN run_tests` runs tests side by side, and a neighbour that
# takes both cores stalls the soak's node long enough to lose messages in roscpp's queues, which
# the soak counts as a failure. Its hidden run_tests target (the one `run_tests` builds) therefore
# waits for every other test of the package, and ctest runs it serially.
get_property(_stocs_targets DIRECTORY PROPERTY BUILDSYSTEM_TARGETS)
set(_stocs_soak "")
set(_stocs_others "")
foreach(_target IN LISTS _stocs_targets)
  if(_target MATCHES "^_run_tests_${PROJECT_NAME}_rostest_.*soak")
    set(_stocs_soak ${_target})
  elseif(_target MATCHES "^_run_tests_${PROJECT_NAME}_(gtest|rostest)_.")
    list(APPEND _stocs_others ${_target})
  endif()
endforeach()
if(NOT _stocs_soak OR NOT _stocs_others)
  message(FATAL_ERROR "the soak's or the other tests' run_tests targets were not found")
endif()
add_dependencies(${_stocs_soak} ${_stocs_others})
string(REGEX REPLACE "^_run_tests_" "_ctest_" _stocs_soak_ctest ${_stocs_soak})
set_tests_properties(${_stocs_soak_ctest} PROPERTIES RUN_SERIAL TRUE)
