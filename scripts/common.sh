# Shared settings for the scripts; sourced, not run.
REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# ROS 1 comes from Debian under /usr; a pyenv or venv Python earlier in PATH breaks catkin_pkg and rospy.
export PATH="/usr/bin:/bin:$PATH"
# The catkin workspace lives beside the checkout, never inside it: a workspace link back into the
# package would let roslaunch and rostest find every launch file twice ("multiple files").
WS="${STOCS_WS:-$(dirname "$REPO")/$(basename "$REPO")_ws}"
JOBS="${STOCS_JOBS:-$(nproc)}"
# ccache keys on paths relative to the folder holding checkout and workspace, so checkouts in
# other folders share hits.
export CCACHE_BASEDIR="$(dirname "$REPO")"
# CMake arguments for the link of the sanitizer and fuzz builds: lld when installed (several times
# quicker than ld.bfd on their large programs) and --as-needed (a program records only the shared
# libraries it uses: a test process of the sanitizer build then loads about 195 rather than 252
# and starts in half the CPU time, which each of that stage's ~380 test processes pays).
LINK_FLAGS="-Wl,--as-needed"
if command -v ld.lld > /dev/null; then LINK_FLAGS="-fuse-ld=lld $LINK_FLAGS"; fi
QUICK_LINK=(-DCMAKE_EXE_LINKER_FLAGS="$LINK_FLAGS" -DCMAKE_SHARED_LINKER_FLAGS="$LINK_FLAGS")
