#!/usr/bin/env bash
# Idempotent set-up: installs exactly the Debian packages this project needs.
# Does nothing (no apt-get at all) when every package is already installed.
# Usage: experiments/setup.sh [--with-report] [--with-blender] [--with-slurm]
#   default          : build + test dependencies (Bazel, Abseil, GoogleTest, ...)
#   --with-report    : also LaTeX for the report PDF
#   --with-blender   : also Blender (generates the report's scene 18, Suzanne)
#   --with-slurm     : also SLURM and munge (a one-node cluster for the runner's test)
#   --with-fuzz      : also clang and libFuzzer (cc/robust/fuzz.sh)
set -euo pipefail

PKGS=(
  bazel-bootstrap        # Bazel 4.2.3: the build system, works offline
  g++                    # C++17 compiler
  libabsl-dev            # Abseil: Status/StatusOr, flags, str_format
  libgtest-dev libgmock-dev  # GoogleTest: unit tests
  libbenchmark-dev       # Google Benchmark: micro-benchmarks
  libassimp-dev          # assimp: mesh import (OBJ, PLY, OFF, AC3D, glTF, ...)
  libpng-dev             # libpng: PNG output
  zlib1g-dev             # zlib: gzip-compressed meshes (.ply.gz)
  libtbb-dev             # oneTBB: parallel rendering / building
  libembree-dev          # Embree 3: the speed to beat
  libhwy-dev             # Google Highway: SIMD and run-time dispatch of the packet kernel
  libpugixml-dev         # pugixml: SuperTuxKart's scene.xml
  nlohmann-json3-dev     # nlohmann-json: result records written and read as JSON
  python3 python3-pandas python3-numpy python3-matplotlib python3-pil python3-tqdm  # analysis, cost images
  pkg-config ca-certificates xz-utils
)
for a in "$@"; do
  case "$a" in
    --with-report) PKGS+=(texlive-latex-recommended texlive-fonts-recommended texlive-latex-extra latexmk lmodern poppler-utils) ;;
    --with-blender) PKGS+=(blender) ;;
    --with-slurm) PKGS+=(slurm-wlm munge) ;;
    --with-fuzz) PKGS+=(clang libclang-rt-14-dev) ;;  # clang 14 and its libFuzzer, ASan, UBSan
    *) echo "setup.sh: unknown option '$a'" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PKGS[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup: done"
