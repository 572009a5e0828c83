#!/usr/bin/env bash
# One-step set-up on a fresh Debian machine: system packages (when root), .venv, the project, npm tools.
# Safe to run again; each step skips what is already done.
set -euo pipefail
cd "$(dirname "$0")/.."

PY=${PYTHON:-python3}
APT_PACKAGES="libusb-1.0-0 libvulkan1 mesa-vulkan-drivers chromium"

if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
  missing=""
  for p in $APT_PACKAGES; do dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"; done
  if [ -n "$missing" ]; then
    echo "==> apt-get install$missing"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $missing >/dev/null
  fi
else
  echo "==> not root: skipping Debian packages ($APT_PACKAGES); install them yourself for rendering/browser tests"
fi

if [ ! -x .venv/bin/python ]; then
  echo "==> creating .venv"
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
# torch first and exactly: anything else pulls GBs of CUDA packages.
.venv/bin/python -m pip install -q torch==2.13.0
echo "==> installing wana and its pinned dependencies"
.venv/bin/python -m pip install -q -e ".[dev]"
# The 'blender' extra (FBX export; about 370 MB): bpy declares numpy<2 yet works with ours, so it goes in
# without its declared dependencies (see pyproject.toml). WANA_SKIP_BLENDER=1 leaves it out.
if [ "${WANA_SKIP_BLENDER:-0}" != "1" ]; then
  if ! .venv/bin/python -c "import importlib.util, sys; sys.exit(importlib.util.find_spec('bpy') is None)"; then
    echo "==> installing the 'blender' extra (bpy, for FBX export)"
    .venv/bin/python -m pip install -q --no-deps bpy==5.0.1 zstandard==0.25.0 cython==3.3.1
  fi
else
  echo "==> WANA_SKIP_BLENDER=1: no bpy; --export fbx will say so"
fi
# A PyPI package `proto-plus` also installs a top-level `proto`; ours must win.
.venv/bin/python -c "import proto, pathlib, sys; p = pathlib.Path(proto.__file__).resolve(); \
sys.exit(0 if p.is_relative_to(pathlib.Path('.').resolve()) else f'wrong proto package imported: {p}')"

for dir in tools/node editor; do
  if [ -f "$dir/package.json" ]; then
    echo "==> npm ci in $dir"
    # npm ci installs exactly the lock file; some npm versions reject a lock that lacks other platforms'
    # optional packages (rollup's), so fall back to npm install, which still honours the locked versions.
    (cd "$dir" && { npm ci --no-audit --no-fund --loglevel=error 2>/dev/null \
      || npm install --no-audit --no-fund --loglevel=error; })
    if grep -q '"build"' "$dir/package.json"; then (cd "$dir" && npm run --silent build); fi
  fi
done
echo "==> set-up done: .venv/bin/wana --help"
