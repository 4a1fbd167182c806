# The repository's files, for the repository tests (sourced): what git tracks or would track,
# else (a copy that is not a checkout) every file outside build folders.
files_of() {
  local root=$1
  if git -C "$root" rev-parse --show-toplevel >/dev/null 2>&1 && [ "$(git -C "$root" rev-parse --show-toplevel)" = "$(cd "$root" && pwd -P)" ]; then
    (cd "$root" && git ls-files -co --exclude-standard)
  else
    (cd "$root" && find . -path './build*' -prune -o -path './.git' -prune -o -type f -print | sed 's#^\./##')
  fi
}
