#!/usr/bin/env bash
# Installs every Debian package sheetgen needs to build, test and run.
# Does nothing (no apt-get update either) when all of them are already present.
set -euo pipefail

PACKAGES=(
  # build
  build-essential cmake ninja-build ccache pkg-config
  # core libraries
  libopenvdb-dev libboost-iostreams-dev libtbb-dev libblosc-dev zlib1g-dev
  libembree-dev libeigen3-dev libsuitesparse-dev nlohmann-json3-dev libcli11-dev
  # exact geometric predicates of the plate mesher (header-only CGAL), the convergence plot (cairo)
  libcgal-dev libgmp-dev libmpfr-dev libcairo2-dev libspectra-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # python module (built for the system Python 3.11 that Debian's Blender runs)
  python3-dev pybind11-dev python3-numpy
  # runtime, reference and check tools
  blender calculix-ccx python3-ezdxf python3-shapely python3-matplotlib python3-pil
  # the solid reference model of tools/sheetgen_tools/solid_reference.py (OpenCASCADE + mesher)
  python3-gmsh
  # STEP of the bent part and flat pattern (native/sheetgen/cad, OpenCASCADE 7.6), and FreeCAD reading them back
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev libocct-data-exchange-dev
  freecad
  # sheetgen-farm (docs/farm.md): Dask distributed (scheduler, workers, client; pulls in python3-dask,
  # python3-tornado), psutil (the farm test looks for solver processes) and the progress bar
  python3-distributed python3-psutil python3-tqdm
  # the drawing sheet read back by its test (pdfinfo, pdftotext, pdftocairo, pdftoppm; docs/drawing.md)
  poppler-utils
  # screenshots of the Blender UI (scripts/make_screenshots.py)
  xvfb
  # function lengths of the C++ code (scripts/function_lengths.py)
  universal-ctags
  # fuzzing and sanitizers (clang + libFuzzer runtime)
  clang libclang-rt-14-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" </dev/null
