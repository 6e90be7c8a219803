#!/usr/bin/env bash
# Checks that the repository points only at itself:
#   1. no tracked file names a document that lives outside the repository (the design notes and
#      rulebooks that once sat in a shared folder beside it): what the code relies on is written
#      in docs/ (docs/conventions.md, docs/collision.md, docs/solver-design.md, docs/style.md,
#      docs/tooling.md);
#   2. every relative Markdown link in a tracked .md file (README.md, docs/*.md, ...) names a file
#      or folder of the repository, and, where it has a #fragment into a Markdown file, a heading
#      of that file (GitHub's anchor rules);
#   3. every citation of a section in the form  docs/<name>.md, "<heading>"  (how comments point at
#      the docs) names an existing heading of that file.
# Lists every offending line as file:line: text and exits 1; exits 0 when there is none.
# Usage: scripts/check_refs.sh   (from anywhere; outside a git checkout it scans the files on disk)
set -euo pipefail
cd "$(dirname "$0")/.."

if git rev-parse --is-inside-work-tree >/dev/null 2>&1 && [[ "$(git rev-parse --show-toplevel)" == "$PWD" ]]; then
  mapfile -t listed < <(git ls-files)
else
  mapfile -t listed < <(find . -path ./.git -prune -o -path './build*' -prune -o -type f -print | sed 's|^\./||' | LC_ALL=C sort)
fi
files=()
for f in "${listed[@]}"; do
  [[ -f "$f" ]] && files+=("$f")
done

failed=0

# 1. Names of documents outside the repository (fixed strings, case-sensitive: docs/style.md and
#    docs/conventions.md are fine, their upper-case namesakes are not). Each is spelt in two
#    pieces so that this file does not match itself.
patterns=(
  '..''/shared' 'shared''/docs'
  'SOLVER''-NOTES' 'COLLISION''-NOTES' 'STYLE''-STUDY'
  'CONVENTIONS''.md' 'MISSION''.md' 'TOOLING''.md' 'STYLE''.md'
)
grep_args=()
for p in "${patterns[@]}"; do grep_args+=(-e "$p"); done
if hits=$(printf '%s\0' "${files[@]}" | xargs -0 grep -nIHF "${grep_args[@]}" --); then
  echo "References to documents outside the repository (write what is needed into docs/ and point there):"
  printf '%s\n' "$hits"
  failed=1
fi

# 2. Relative Markdown links. awk prints "line<TAB>target" for every inline link or image
#    ([text](target), ![alt](target)) and every reference definition ([id]: target), outside
#    fenced code blocks and inline code spans.
extract_links() {
  awk '
    /^[ \t]*(```|~~~)/ { fence = !fence; next }
    fence { next }
    {
      line = $0
      gsub(/`[^`]*`/, "", line)
      if (match(line, /^[ \t]*\[[^]]+\]:[ \t]*[^ \t]+/)) {
        def = substr(line, RSTART, RLENGTH)
        sub(/^[ \t]*\[[^]]+\]:[ \t]*/, "", def)
        print NR "\t" def
      }
      while (match(line, /\]\([^)]*\)/)) {
        target = substr(line, RSTART + 2, RLENGTH - 3)
        line = substr(line, RSTART + RLENGTH)
        sub(/^[ \t]+/, "", target)
        sub(/[ \t].*$/, "", target)   # drop a "title"
        gsub(/^<|>$/, "", target)
        if (target != "") print NR "\t" target
      }
    }' "$1"
}

# GitHub's heading anchors: lower case, drop everything but letters, marks, digits, spaces,
# hyphens and underscores, spaces become hyphens; repeated headings get -1, -2, ...
heading_anchors() {
  awk '
    /^[ \t]*(```|~~~)/ { fence = !fence; next }
    fence { next }
    /^#+[ \t]/ { sub(/^#+[ \t]+/, ""); sub(/[ \t]+#*[ \t]*$/, ""); print }' "$1" |
  perl -CSD -ne 'chomp; $_ = lc; s/[^\p{L}\p{M}\p{N}\p{Pc}\- ]//g; s/ /-/g;
                 $n = $seen{$_}++; print $n ? "$_-$n\n" : "$_\n";'
}

declare -A tracked=()
declare -A folders=()
for f in "${files[@]}"; do
  tracked["$f"]=1
  d=$f
  while [[ "$d" == */* ]]; do
    d=${d%/*}
    [[ -n "${folders[$d]:-}" ]] && break
    folders["$d"]=1
  done
done

link_errors=()
for md in "${files[@]}"; do
  [[ "$md" == *.md ]] || continue
  while IFS=$'\t' read -r line target; do
    [[ "$target" =~ ^[a-zA-Z][a-zA-Z0-9+.-]*: ]] && continue  # http:, https:, mailto: ...
    path=${target%%#*}
    fragment=""
    [[ "$target" == *"#"* ]] && fragment=${target#*#}
    path=${path//%20/ }
    if [[ -z "$path" ]]; then
      resolved=$md
    elif [[ "$path" == /* ]]; then
      resolved=$(realpath -m --relative-to=. "./${path#/}")
    else
      resolved=$(realpath -m --relative-to=. "$(dirname "$md")/$path")
    fi
    if [[ "$resolved" == ..* || ( -z "${tracked[$resolved]:-}" && -z "${folders[$resolved]:-}" ) ]]; then
      link_errors+=("$md:$line: link to $target: no such file in the repository")
      continue
    fi
    if [[ -n "$fragment" && "$resolved" == *.md && -f "$resolved" ]]; then
      if ! heading_anchors "$resolved" | grep -qxF -- "$fragment"; then
        link_errors+=("$md:$line: link to $target: no heading with that anchor in $resolved")
      fi
    fi
  done < <(extract_links "$md")
done
if ((${#link_errors[@]})); then
  echo "Broken relative Markdown links:"
  printf '%s\n' "${link_errors[@]}"
  failed=1
fi

# 3. Section citations in comments and prose: docs/<name>.md, "<heading>" (possibly wrapped over a
#    comment line break) must name a file of the repository and a heading in it.
# shellcheck disable=SC2016  # the Perl program is meant to be single-quoted
section_errors=$(printf '%s\0' "${files[@]}" | xargs -0 perl -CSD -e '
  use strict; use warnings;
  my %cache;
  sub headings {
    my ($f) = @_;
    return $cache{$f} //= do {
      my %h; my $fence = 0;
      if (open my $fh, "<:encoding(UTF-8)", $f) {
        while (<$fh>) {
          if (/^\s*(```|~~~)/) { $fence = !$fence; next }
          next if $fence;
          $h{$1} = 1 if /^#+\s+(.*?)\s*#*\s*$/;
        }
      }
      \%h;
    };
  }
  for my $file (@ARGV) {
    next unless -T $file;
    open my $fh, "<:encoding(UTF-8)", $file or next;
    my $text = do { local $/; <$fh> };
    my $gap = qr{\s*(?:\n\s*(?://+|\#+)?\s*)?};
    while ($text =~ m{(docs/[A-Za-z0-9_.-]+\.md)(?:\]\([^)\n]*\))?,$gap"([^"\n]+(?:\n\s*(?://+|\#+)?\s*[^"\n]+)?)"}g) {
      my ($doc, $heading, $at) = ($1, $2, $-[0]);
      $heading =~ s{\s*\n\s*(?://+|\#+)?\s*}{ }g;
      my $line = 1 + (substr($text, 0, $at) =~ tr/\n//);
      if (!-f $doc) { print "$file:$line: $doc: no such file in the repository\n" }
      elsif (!headings($doc)->{$heading}) { print "$file:$line: $doc has no heading \"$heading\"\n" }
    }
  }' || true)
if [[ -n "$section_errors" ]]; then
  echo "Citations of a section that does not exist:"
  printf '%s\n' "$section_errors"
  failed=1
fi

if ((failed)); then exit 1; fi
echo "check_refs: every reference points inside the repository"
