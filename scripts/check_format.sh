#!/usr/bin/env bash
# Checks that every C++ file of the repository is formatted as .clang-format says (Debian 12's
# clang-format 14; another version may wrap a few lines differently) and that no line of them is
# longer than its column limit, 130 characters (comments and strings included). Lists the
# offenders and exits 1; exits 0 when there is none.
# To format: git ls-files '*.hpp' '*.cpp' | xargs clang-format -i
# Usage: scripts/check_format.sh   (from anywhere; outside a git checkout it scans the files on disk)
set -euo pipefail
cd "$(dirname "$0")/.."

if git rev-parse --is-inside-work-tree >/dev/null 2>&1 && [[ "$(git rev-parse --show-toplevel)" == "$PWD" ]]; then
  mapfile -t files < <(git ls-files '*.hpp' '*.cpp')
else
  mapfile -t files < <(find . -path ./.git -prune -o -path './build*' -prune -o -type f \( -name '*.hpp' -o -name '*.cpp' \) -print |
                       sed 's|^\./||' | LC_ALL=C sort)
fi

format=$(command -v clang-format-14 || command -v clang-format || true)
if [[ -z "$format" ]]; then
  echo "check_format: clang-format not found (scripts/setup.sh test installs it)" >&2
  exit 1
fi

failed=0
if ! "$format" --dry-run --Werror "${files[@]}"; then
  echo "check_format: the files above differ from .clang-format ($("$format" --version))" >&2
  failed=1
fi
limit=$(sed -n 's/^ColumnLimit: *//p' .clang-format)
# Characters, not bytes: the comments use UTF-8 (×, –, ²). (perl is in every Debian; mawk counts bytes.)
if ! perl -CSD -ne 'chomp; if (length($_) > '"$limit"') { print "$ARGV:$.: ", length($_), " characters\n"; $bad = 1 }
                    close ARGV if eof; END { exit($bad ? 1 : 0) }' "${files[@]}"; then
  echo "check_format: lines over the column limit of $limit" >&2
  failed=1
fi
exit $failed
