#!/usr/bin/env bash
# Pack this checkout's simulation stack (the venv's Python interpreter and standard library,
# numpy, pyyaml and a stripped pybullet; no torch) into one xz tarball of about 20 MB, so that
# simulation-only work (get-up searches and screens, matches, benchmarks) runs on a many-core
# machine whose own Python cannot install pybullet (session 18: a lent machine with Python 3.12
# and no network, where only a cp311 pybullet wheel exists). Learning needs torch and stays here.
#
#   scripts/device/pack_python.sh .pyb/py.tar.xz        # here; keep .pyb/ out of git
#   # there, in the checkout's root:
#   mkdir -p /tmp/b && tar xJf .pyb/py.tar.xz -C /tmp/b && B=/tmp/b/py
#   export LD_LIBRARY_PATH=$B/lib PYTHONHOME=$B PYTHONPATH=$B/site:$PWD PYTHONNOUSERSITE=1
#   PYTHON=$B/bin/python3.11 scripts/get_up/search_fanout.sh OUT_DIR
#
# The interpreter needs glibc and libstdc++ at least as new as this machine's (Debian 12).
set -euo pipefail
out=${1:?usage: pack_python.sh OUT.tar.xz}
cd "$(dirname "$0")/../.."
venv=.venv
base=$("$venv/bin/python" -c 'import sys; print(sys.base_prefix)')
version=$("$venv/bin/python" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/py/bin" "$work/py/lib" "$work/py/site"
cp "$base/bin/python$version" "$work/py/bin/"
cp "$base"/lib/libpython"$version".so* "$work/py/lib/" 2>/dev/null || true
(cd "$base/lib" && tar cf - --exclude=test --exclude=site-packages --exclude=__pycache__ \
  --exclude=idlelib --exclude=tkinter --exclude=turtledemo --exclude=ensurepip \
  --exclude=lib2to3 --exclude="config-$version*" "python$version") | (cd "$work/py/lib" && tar xf -)
for package in numpy numpy.libs yaml _yaml; do
  [ -e "$site/$package" ] && cp -r "$site/$package" "$work/py/site/"
done
cp "$site"/pybullet.*.so "$work/py/site/"
find "$work/py" -name __pycache__ -prune -exec rm -rf {} +
find "$work/py/site/numpy" -name tests -prune -exec rm -rf {} +
strip --strip-unneeded "$work"/py/site/pybullet.*.so "$work"/py/lib/libpython*.so* 2>/dev/null || true
# check the pack before writing it
LD_LIBRARY_PATH="$work/py/lib" PYTHONHOME="$work/py" PYTHONPATH="$work/py/site" PYTHONNOUSERSITE=1 \
  "$work/py/bin/python$version" -c "import numpy, yaml, pybullet" >/dev/null
mkdir -p "$(dirname "$out")"
tar cf - -C "$work" py | xz -T0 -6 >"$out"
echo "$out: $(du -h "$out" | cut -f1)"
