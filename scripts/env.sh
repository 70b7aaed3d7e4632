# Sourced by the other scripts: the environment catkin and rostest need on Debian 12.
# Debian's python must come first: another python3 earlier on PATH breaks catkin's cmake.
export PATH="/usr/bin:${PATH}"
FREEFORM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export FREEFORM_ROOT
export FREEFORM_BUILD="${FREEFORM_BUILD:-${FREEFORM_ROOT}/build}"
export CCACHE_DIR="${CCACHE_DIR:-${HOME}/.cache/ccache}"
# Two cores here; the PCL headers are heavy, more jobs only thrash.
export FREEFORM_JOBS="${FREEFORM_JOBS:-$(nproc)}"
