# Sourced (`. .ci/without-bubblewrap.sh`): hides bwrap from PATH in this shell, as on a machine without
# bubblewrap; the grader then runs student code in its subprocess mode. Used by .ci/run; source it by hand
# to run some test files that way (`. .ci/without-bubblewrap.sh && python -m pytest tests/sandbox -n 2`).
#
# Each PATH folder holding a bwrap is replaced, in place, by a folder of links to everything else in it
# (bwrap sits in /usr/bin with everything else, so no entry can simply be dropped). Folders without a bwrap
# stay as they are: an activated venv's bin/ must stay itself, since a link to its python from another folder
# starts the base interpreter outside the venv (Python finds pyvenv.cfg beside the path it was called by).
# Sets SIMIAM_BWRAP_HIDDEN to the folder of links; returns 1 if a bwrap is still found.

_simiam_hide_bwrap() {
  local links dir exe name n=0 path="" entry
  local -a dirs
  links="$(mktemp -d "${TMPDIR:-/tmp}/simiam-no-bwrap.XXXXXX")" || return 1
  IFS=: read -ra dirs <<<"$PATH"
  for dir in "${dirs[@]}"; do
    entry="$dir"
    if [ -n "$dir" ] && [ -e "$dir/bwrap" ]; then
      n=$((n + 1))
      entry="$links/$n"
      mkdir "$entry" || return 1
      for exe in "$dir"/*; do
        name="${exe##*/}"
        [ "$name" = bwrap ] || ln -s "$exe" "$entry/$name"
      done
    fi
    path="${path:+$path:}$entry"
  done
  export PATH="$path"
  export SIMIAM_BWRAP_HIDDEN="$links"
  hash -r
  if command -v bwrap >/dev/null 2>&1; then
    echo "bwrap still on PATH: $(command -v bwrap)" >&2
    return 1
  fi
  return 0
}

_simiam_hide_bwrap
