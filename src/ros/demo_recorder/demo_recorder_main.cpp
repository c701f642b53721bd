// The demo's listener (see demo_recorder.h).
#include "stocs_ros/common/run_node.h"
#include "stocs_ros/demo_recorder/demo_recorder.h"

int main(int argc, char** argv) {
  return stocs_ros::runNode<stocs_ros::DemoRecorder>(argc, argv, "demo_recorder");
}
