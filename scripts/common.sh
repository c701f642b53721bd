# Shared settings for the scripts; sourced, not run.
REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# ROS 1 comes from Debian under /usr; a pyenv or venv Python earlier in PATH breaks catkin_pkg and rospy.
export PATH="/usr/bin:/bin:$PATH"
WS="${STOCS_WS:-$REPO/build/ws}"
JOBS="${STOCS_JOBS:-$(nproc)}"
# ccache keys on paths relative to the repository, so checkouts in other folders share hits.
export CCACHE_BASEDIR="$REPO"
