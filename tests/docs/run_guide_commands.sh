#!/usr/bin/env bash
# run_guide_commands.sh PAGE.md SOURCE_DIR CONTACTLAB_EXE — runs every ```sh block of a guide page
# as a user would type it, in order, in one fresh directory (with `scenes/` beside it and
# `contactlab` on the PATH), so the guide cannot rot. A block that cannot run here says why on the
# line before its fence: <!-- docs-test: skip (why) -->  (a display, a real device, minutes of CPU,
# a build of its own). Any failing command fails the test and names the page and line.
set -euo pipefail
page=$1 source_dir=$2 exe=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/contactlab-docs-XXXXXX")
trap 'rm -rf "$work"' EXIT
ln -s "$source_dir/scenes" "$work/scenes"
bin="$work/.bin"; mkdir "$bin"; ln -s "$exe" "$bin/contactlab"
export PATH="$bin:$PATH"

ran=0 skipped=0 line_no=0 in_block=0 skip_block=0 last_text="" block="" start=0
while IFS= read -r line || [ -n "$line" ]; do
  line_no=$((line_no + 1))
  if [ $in_block -eq 0 ]; then
    if [[ "$line" == '```sh' ]]; then
      in_block=1 block="" start=$line_no skip_block=0
      if [[ "$last_text" =~ ^\<\!--\ docs-test:\ skip\ \((.+)\)\ --\>$ ]]; then skip_block=1; fi
    elif [[ -n "${line// /}" ]]; then
      last_text=$line
    fi
    continue
  fi
  if [[ "$line" == '```' ]]; then
    in_block=0 last_text=""
    if [ $skip_block -eq 1 ]; then skipped=$((skipped + 1)); continue; fi
    echo "== $page:$start"
    printf '%s\n' "$block"
    if ! (cd "$work" && timeout 600 bash -euo pipefail -c "$block") >"$work/.out" 2>&1; then
      tail -n 40 "$work/.out"
      echo "FAILED: the block at $page:$start" >&2
      exit 1
    fi
    ran=$((ran + 1))
    continue
  fi
  block+="$line"$'\n'
done <"$page"
[ $in_block -eq 0 ] || { echo "$page:$start: a \`\`\`sh block is never closed" >&2; exit 1; }
echo "$page: $ran block(s) ran, $skipped skipped with a reason"
