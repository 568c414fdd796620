# Sourced by scripts/ab-runtime.sh and scripts/ab-wavefront.sh: the revisions named on the
# command line, each checked out in a temporary worktree and built there (the working
# tree in a temporary folder of its own, so that build/ keeps its configuration).
# Expects $here (the checkout) and $ab_tool (the script's name, for messages); sets $out,
# a temporary folder removed with its worktrees at exit.
out="$(mktemp -d)"
ab_cleanup() {
  for w in "$out"/tree-*; do [ -d "$w" ] && git -C "$here" worktree remove --force "$w" > /dev/null 2>&1 || true; done
  rm -rf "$out"
}
trap ab_cleanup EXIT

# ab_revisions REV_A [REV_B] [OPTIONS...]: sets rev_a, rev_b (empty: the working tree) and
# ab_options, the rest.
ab_revisions() {
  rev_a="$1"
  shift
  rev_b=""
  if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then rev_b="$1"; shift; fi
  ab_options=("$@")
}

# ab_build NAME REV TARGET [CMAKE_ARGS...]: configures REV (the working tree when empty)
# in Release with CMAKE_ARGS and builds TARGET; sets ab_src and ab_bin.
ab_build() {
  local name="$1" rev="$2" target="$3"
  shift 3
  if [ -z "$rev" ]; then
    ab_src="$here"
    ab_bin="$out/build-working-tree"
  else
    git -C "$here" rev-parse --verify --quiet "$rev^{commit}" > /dev/null || { echo "$ab_tool: no revision $rev" >&2; exit 1; }
    ab_src="$out/tree-$name"
    git -C "$here" worktree add --detach --quiet "$ab_src" "$rev"
    ab_bin="$ab_src/build"
  fi
  echo "$ab_tool: building $target of ${rev:-the working tree}" >&2
  cmake -S "$ab_src" -B "$ab_bin" -DCMAKE_BUILD_TYPE=Release "$@" > "$out/cmake.log" 2>&1 ||
    { cat "$out/cmake.log" >&2; echo "$ab_tool: cmake failed for ${rev:-the working tree}" >&2; exit 1; }
  cmake --build "$ab_bin" -j2 --target "$target" > "$out/build.log" 2>&1 ||
    { cat "$out/build.log" >&2; echo "$ab_tool: the build failed for ${rev:-the working tree}" >&2; exit 1; }
}
