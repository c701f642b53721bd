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
