# ccache's settings for every build of the project; sourced (with ROOT set) by
# build.sh, sanitize.sh and fuzz.sh.
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/ccache}"
# Paths under the checkout are hashed relative to it, so a fresh clone in
# another folder reuses the cache of an earlier one (the CI's case).
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
