#!/usr/bin/env bash
# Fetches the example meshes: Debian's libcgal-demo package ships CGAL's data.tar.gz; its data/meshes/*.off go
# into data/meshes/ (git-ignored). Idempotent: does nothing when the meshes are already there.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dest="$root/data/meshes"
if [ -f "$dest/camel.off" ] && [ -f "$dest/cow.off" ]; then
  exit 0
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
# apt-get download runs as the unprivileged _apt user where it can; the temp folder must be writable by it.
chmod 755 "$tmp"
if ! apt-get download libcgal-demo >/dev/null 2>&1; then
  apt-get update -qq
  apt-get download libcgal-demo
fi
dpkg-deb -x libcgal-demo_*.deb pkg
mkdir -p "$dest"
tar -xzf pkg/usr/share/doc/libcgal-dev/data.tar.gz -C "$tmp" data/meshes
cp "$tmp"/data/meshes/*.off "$dest"/
echo "meshes: $(ls "$dest" | wc -l) files in $dest"
