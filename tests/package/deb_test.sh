#!/usr/bin/env bash
# The Debian package: `cpack -G DEB` in the build tree, then
#   - its control data and contents (the command, the library, headers, CMake and pkg-config
#     files, the data) and its dependencies found by dpkg-shlibdeps;
#   - unpacked anywhere (dpkg -x), its pcsim runs and validates from another folder, finding
#     its data relative to itself;
#   - as root: installed with dpkg -i, `pcsim run` and `pcsim validate` from another folder,
#     then removed with dpkg --purge, leaving none of its files. A pcsim package this test did
#     not install is left alone (the test fails instead).
#
#   deb_test.sh SOURCE_DIR BINARY_DIR WORK_DIR
set -euo pipefail
source=$1 binary=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

cpack -G DEB -B "$work/cpack" --config "$binary/CPackConfig.cmake" >"$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; fail "cpack -G DEB"; }
deb=$(find "$work/cpack" -maxdepth 1 -name 'pcsim_*.deb')
[ -f "$deb" ] || fail "cpack made no pcsim_*.deb"
echo "package: $(basename "$deb")"

dpkg-deb --field "$deb" Package | grep -qx pcsim || fail "the package is not named pcsim"
depends=$(dpkg-deb --field "$deb" Depends)
for library in libc6 libstdc++6 libfmt9 libpugixml1v5 libtomlplusplus3; do
  [[ $depends == *"$library"* ]] || fail "Depends lacks $library: $depends"
done
echo "ok: Depends: $depends"
dpkg-deb --contents "$deb" | awk '{print $NF}' | sed 's#^\./#/#' >"$work/contents"
for path in /usr/bin/pcsim /usr/include/pagecache/outputs.hpp /usr/include/pagecache/version.hpp /usr/share/pcsim/validation/paper/README.md \
  /usr/share/pcsim/scenarios/paper/exp1.toml /usr/share/pcsim/inputs/README.md /usr/share/doc/pcsim/LICENSE; do
  grep -qx "$path" "$work/contents" || fail "the package lacks $path"
done
for pattern in '/libpagecache\.a$' '/pkgconfig/pagecache\.pc$' '/cmake/pagecache/pagecacheConfig\.cmake$' '/cmake/pagecache/pagecacheTargets\.cmake$'; do
  grep -q "$pattern" "$work/contents" || fail "the package lacks a file matching $pattern"
done
if grep -q "$source\|$binary" "$work/contents"; then fail "the package holds a path of the build machine"; fi
echo "ok: contents ($(grep -vc '/$' "$work/contents") entries)"

# pcsim run and validate from a folder that is neither the package's nor the sources'.
reference=$work/reference
"$binary/bin/pcsim" run --out "$reference" --quiet
exercise() {  # exercise PCSIM WHAT
  local folder share
  folder=$(mktemp -d "$work/elsewhere.XXXX")
  share=$(dirname "$(dirname "$(command -v "$1")")")/share/pcsim
  (
    cd "$folder"
    "$1" --version | grep -q pcsim || fail "$2: pcsim --version"
    "$1" run --quiet || fail "$2: pcsim run"
    for f in timeline.csv memory.csv cache.csv summary.json report.html; do
      cmp -s "pcsim-out/$f" "$reference/$f" || fail "$2: pcsim run wrote a $f that differs from the build's"
    done
    "$1" run "$share/scenarios/paper/exp2.toml" --out exp2 --quiet || fail "$2: pcsim run of a shipped scenario"
    "$1" validate --json v.json >validate.txt || { cat validate.txt; fail "$2: pcsim validate"; }
    grep -q '"mean_error_pct"' v.json || fail "$2: pcsim validate wrote no errors"
    [ -s validate-report.html ] || fail "$2: pcsim validate wrote no report"
  )
  echo "ok: $2: pcsim run and pcsim validate from another folder"
}
dpkg-deb -x "$deb" "$work/unpacked"
exercise "$work/unpacked/usr/bin/pcsim" "unpacked with dpkg -x into $work/unpacked"

if [ "$(id -u)" != 0 ]; then
  echo "not root: dpkg -i was not tried (CI runs this test as root)"
  exit 0
fi
if dpkg-query -W -f='${Status}' pcsim 2>/dev/null | grep -q 'installed'; then
  fail "a pcsim package is installed on this machine already; this test leaves it alone (dpkg --purge pcsim, then run it again)"
fi
installed=false
cleanup() { if $installed; then dpkg --purge pcsim >/dev/null 2>&1 || true; fi; }
trap cleanup EXIT
dpkg -i "$deb" >"$work/dpkg-install.log" 2>&1 || { cat "$work/dpkg-install.log"; installed=true; fail "dpkg -i"; }
installed=true
[ "$(command -v pcsim)" = /usr/bin/pcsim ] || fail "pcsim on the PATH is $(command -v pcsim), not /usr/bin/pcsim"
exercise pcsim "installed with dpkg -i"
mapfile -t files < <(dpkg-query -L pcsim | while read -r f; do [ -f "$f" ] && echo "$f"; done)
dpkg --purge pcsim >"$work/dpkg-purge.log" 2>&1 || { cat "$work/dpkg-purge.log"; fail "dpkg --purge pcsim"; }
installed=false
if dpkg-query -W -f='${Status}' pcsim 2>/dev/null | grep -q 'installed'; then fail "pcsim is still installed after dpkg --purge"; fi
left=0
for f in "${files[@]}"; do
  if [ -e "$f" ]; then echo "left behind: $f"; left=1; fi
done
[ $left = 0 ] || fail "dpkg --purge left files of the package"
for dir in /usr/share/pcsim /usr/include/pagecache /usr/share/doc/pcsim; do
  [ ! -e "$dir" ] || fail "dpkg --purge left $dir"
done
echo "ok: installed with dpkg -i and removed with dpkg --purge (${#files[@]} files, none left)"
