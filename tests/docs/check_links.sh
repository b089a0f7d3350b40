#!/usr/bin/env bash
# check_links.sh SOURCE_DIR FILE.md... — every relative link and image in the guide resolves (the
# file exists; a #anchor names a heading of the target page, by GitHub's rule for heading ids),
# and no page speaks of the project's internal issue numbers, which users never see.
set -euo pipefail
source_dir=$1; shift
fail=0

# GitHub's heading id: lower case, punctuation dropped (letters, digits, spaces, '-' and '_'
# stay), each space a '-'.
slugs() {
  awk '/^```/{f=!f; next} !f && /^#+ /{sub(/^#+ +/, ""); print}' "$1" |
    tr '[:upper:]' '[:lower:]' | sed -E 's/[^a-z0-9 _-]//g; s/ /-/g'
}

for page in "$@"; do
  dir=$(dirname "$page")
  rel=${page#"$source_dir"/}
  # Links outside code fences and inline code: ](target)
  while IFS= read -r target; do
    case "$target" in http://*|https://*|mailto:*) continue ;; esac
    path=${target%%#*}
    anchor=""
    [[ "$target" == *"#"* ]] && anchor=${target#*#}
    if [ -z "$path" ]; then file=$page; else file="$dir/$path"; fi
    if [ ! -e "$file" ]; then
      echo "$rel: link to a missing file: $target" >&2; fail=1; continue
    fi
    if [ -n "$anchor" ] && [[ "$file" == *.md ]]; then
      if ! slugs "$file" | grep -qxF -- "$anchor"; then
        echo "$rel: link to a missing heading: $target" >&2; fail=1
      fi
    fi
  done < <(awk '/^```/{f=!f; next} !f' "$page" | sed -E 's/`[^`]*`//g' | grep -oE '\]\([^) ]+\)' | sed -E 's/^\]\((.*)\)$/\1/')
  if grep -nE '\b[Ii]ssues? #?[0-9]+' "$page" >&2; then
    echo "$rel: names an internal issue number (above)" >&2; fail=1
  fi
done
[ $fail -eq 0 ] && echo "links: $# page(s), every relative link resolves"
exit $fail
