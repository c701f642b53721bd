#!/usr/bin/env bash
# Installs every Debian 12 package stocs_ros needs to build, test and run (ROS 1 from Debian).
# Skips apt-get when everything is already installed, so repeated runs are quick.
set -euo pipefail

PACKAGES=(
  build-essential cmake ccache pkg-config git
  ros-base-dev catkin python3-catkin-pkg python3-rostest python3-roslaunch python3-rosunit
  libpcl-ros-dev libpcl-conversions-dev libcv-bridge-dev
  libtf2-ros-dev libtf2-eigen-dev libtf2-geometry-msgs-dev
  ros-message-generation libvisualization-msgs-dev libstd-srvs-dev libdiagnostic-msgs-dev
  libnodeletlib-dev libnodelet-dev libdynamic-reconfigure-config-init-mutex-dev
  python3-dynamic-reconfigure python3-geometry-msgs python3-sensor-msgs python3-tf2-msgs
  python3-visualization-msgs python3-std-msgs python3-numpy python3-pil
  libpcl-dev libopencv-dev libopencv-contrib-dev libeigen3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libyaml-cpp-dev libcli11-dev libfmt-dev libspdlog-dev libnanoflann-dev
  libxxhash-dev
  # The segmentation network node and `--prob onnx:` (OpenCV DNN) and its image subscription.
  libopencv-dnn-dev libimage-transport-dev
  # Model files in OBJ, STL, DAE, glTF (src/io/assimp_model.cpp); assimp-utils' `assimp export`
  # makes the glTF of scripts/export_test_meshes.py.
  libassimp-dev assimp-utils
  gnuplot-nox
  clang libclang-rt-14-dev libomp-14-dev
  # lld links the sanitizer and fuzz builds' programs (scripts/common.sh: QUICK_LINK).
  lld
  # What README's commands use: rosrun, tf_echo, rosbag, rviz (headless under xvfb-run, which
  # needs xauth; Xvfb draws OpenGL with Mesa's software renderer), and the Python messages that
  # rostopic and rosservice load for every type they echo or call. catkin_lint checks package.xml
  # and CMake in scripts/run_tests.sh.
  rosbash tf-tools python3-rosbag rviz xvfb xauth libgl1-mesa-dri
  python3-rostopic python3-rosservice python3-rosnode python3-genpy
  python3-diagnostic-msgs python3-std-srvs python3-rosgraph-msgs
  catkin-lint
  # scripts/rviz_screenshots.sh takes its screenshots with ImageMagick's import.
  imagemagick
  # Open3D 0.16 for the o3d-ransac and o3d-fgr baselines of `stocs bench` (built only where found;
  # 16 packages, about 90 MB installed, most of it Filament, Embree and Open3D itself).
  libopen3d-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${#missing[@]} packages: ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
