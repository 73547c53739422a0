#!/usr/bin/env bash
# Builds the Debian package eip2mqtt_<version>_<arch>.deb from a built tree, with dpkg-deb alone:
# the stripped binary in /usr/bin, the unit in /lib/systemd/system (where Debian 12 keeps units),
# the example configuration in /etc/eip2mqtt as conffiles, the man page eip2mqtt(1), and the
# README with docs/ in /usr/share/doc/eip2mqtt. The state directory is the unit's
# StateDirectory=, so the package ships none.
#   tools/package.sh [--build-dir DIR] [--out DIR] [--no-build]
# (default: build/, built with tools/build.sh when it has no binary yet; --no-build packages the
# binary as it is, which is what the tests do; the package is written to --out, default the
# current directory, and its path printed)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=$root/build
out=$PWD
build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build_dir=$(cd "${2:?}" && pwd); shift 2 ;;
    --out) out=${2:?}; shift 2 ;;
    --no-build) build=0; shift ;;
    *) echo "usage: $0 [--build-dir DIR] [--out DIR] [--no-build]" >&2; exit 2 ;;
  esac
done

binary=$build_dir/eip2mqtt
if [ "$build" = 1 ]; then
  if [ -f "$build_dir/build.ninja" ] || [ -f "$build_dir/Makefile" ]; then
    cmake --build "$build_dir" --target eip2mqtt >&2
  else
    (cd "$root" && tools/build.sh release eip2mqtt) >&2
    binary=$root/build/eip2mqtt
  fi
fi
[ -x "$binary" ] || { echo "package: no binary at $binary (build it, or drop --no-build)" >&2; exit 1; }

version=$("$binary" --version | awk '{print $2}')
arch=$(dpkg --print-architecture)
maintainer=${EIP2MQTT_MAINTAINER:-"eip2mqtt maintainers <maintainers@users.noreply.h-seed-80d05187.example>"}
# Dates from the last commit, so that two packages of one commit are the same bytes.
epoch=$(git -C "$root" log -1 --format=%ct 2>/dev/null || date +%s)
export SOURCE_DATE_EPOCH=$epoch

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pkg=$work/eip2mqtt
doc=$pkg/usr/share/doc/eip2mqtt
umask 022
install -d "$pkg/DEBIAN" "$pkg/usr/bin" "$pkg/lib/systemd/system" "$pkg/etc/eip2mqtt" \
  "$pkg/usr/share/man/man1" "$doc"

# The binary without its debug information and symbol table, as dh_strip leaves it.
install -m 0755 "$binary" "$pkg/usr/bin/eip2mqtt"
strip --remove-section=.comment --remove-section=.note --strip-unneeded "$pkg/usr/bin/eip2mqtt"

# The unit names the installed paths; its source names /usr/local's, as `cmake --install` does.
sed 's#/usr/local/#/usr/#g' "$root/systemd/eip2mqtt.service" >"$pkg/lib/systemd/system/eip2mqtt.service"
chmod 0644 "$pkg/lib/systemd/system/eip2mqtt.service"

install -m 0644 "$root/etc/eip2mqtt/eip2mqtt.yaml" "$root/etc/eip2mqtt/turbine1.csv" "$pkg/etc/eip2mqtt/"
printf '%s\n' /etc/eip2mqtt/eip2mqtt.yaml /etc/eip2mqtt/turbine1.csv >"$pkg/DEBIAN/conffiles"

gzip -9n <"$root/man/eip2mqtt.1" >"$pkg/usr/share/man/man1/eip2mqtt.1.gz"

install -m 0644 "$root/README.md" "$root/packaging/debian/copyright" "$doc/"
cp -r "$root/docs" "$doc/docs"
find "$doc/docs" -type d -exec chmod 0755 {} + -o -type f -exec chmod 0644 {} +
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
{
  echo "eip2mqtt ($version) unstable; urgency=medium"
  echo
  echo "  * Built from commit $commit by tools/package.sh."
  echo
  echo " -- $maintainer  $(date -u -R -d "@$epoch")"
} | gzip -9n >"$doc/changelog.gz"

for script in postinst prerm postrm; do
  install -m 0755 "$root/packaging/debian/$script" "$pkg/DEBIAN/$script"
done

# Depends from the libraries the binary links, as dh_shlibdeps finds them.
mkdir -p "$work/source/debian"
printf 'Source: eip2mqtt\n\nPackage: eip2mqtt\nArchitecture: any\n' >"$work/source/debian/control"
if ! shlibs=$(cd "$work/source" && dpkg-shlibdeps -O -e"$pkg/usr/bin/eip2mqtt" 2>"$work/shlibdeps.log"); then
  cat "$work/shlibdeps.log" >&2
  exit 1
fi
depends=$(sed -n 's/^shlibs:Depends=//p' <<<"$shlibs")
[ -n "$depends" ] || { echo "package: dpkg-shlibdeps found no dependencies" >&2; exit 1; }
# libpcap and SQLite are loaded where they are used (dlopen), so dpkg-shlibdeps does not see
# them: the packages that hold them, by hand.
for soname in libpcap.so.0.8 libsqlite3.so.0; do
  holder=$(dpkg-query -S "*/$(dpkg-architecture -qDEB_HOST_MULTIARCH)/$soname" |
    cut -d: -f1 | head -n 1)
  [ -n "$holder" ] || { echo "package: no package holds $soname" >&2; exit 1; }
  depends="$depends, $holder"
done
size=$(du -k -s --exclude=DEBIAN "$pkg" | cut -f1)
sed -e "s|@VERSION@|$version|" -e "s|@ARCH@|$arch|" -e "s|@MAINTAINER@|$maintainer|" \
  -e "s|@INSTALLED_SIZE@|$size|" -e "s|@DEPENDS@|$depends|" \
  "$root/packaging/debian/control.in" >"$pkg/DEBIAN/control"

# Conffiles are left out, as dh_md5sums leaves them: dpkg keeps their sums itself.
(cd "$pkg" && find . \( -path ./DEBIAN -o -path ./etc \) -prune -o -type f -printf '%P\0' | sort -z |
  xargs -0 md5sum) >"$pkg/DEBIAN/md5sums"
chmod 0644 "$pkg/DEBIAN/control" "$pkg/DEBIAN/conffiles" "$pkg/DEBIAN/md5sums"
find "$pkg" -exec touch -h -d "@$epoch" {} +

mkdir -p "$out"
deb=$(cd "$out" && pwd)/eip2mqtt_${version}_${arch}.deb
dpkg-deb --root-owner-group -Zxz --build "$pkg" "$deb" >/dev/null
echo "$deb"
