#!/usr/bin/env bash
# Installs the Debian packages shapedem needs to build, test and run its
# documented examples: the one install step there is. As root it runs
# apt-get; otherwise it prints the exact command to run.
#
#   scripts/deps.sh            install what is missing
#   scripts/deps.sh --list     print the package list, one per line, and exit
#                              (README.md shows it: `make docs` copies it there)
#
# tests/cli/deps_complete.sh checks that this list provides every command a
# test or README command calls and every Python module a tracked script
# imports: a package used by hand and missing here fails the suite.
set -euo pipefail

# build: compiler, CMake, YAML parser, HDF5 (checkpoints, io/checkpoint.c). tests: independent libraries used as
# oracles (libccd for GJK/EPA, qhull for overlap volumes). Python 3 with
# matplotlib (numpy comes with it): the analysis and plotting scripts (examples/,
# docs/validation/, scripts/), which tests run; Debian's interpreter is the
# one these modules install into (/usr/bin/python3). python3-h5py: the
# reading of a checkpoint from Python that docs/checkpoints.md shows (run by
# cli.checkpoint_h5py). git: the suite lists the
# tracked files it checks. clang with libclang-rt-dev (which brings
# libclang-rt-14-dev, the libFuzzer and sanitizer runtimes): `make fuzz`
# (tests/fuzz). valgrind: the memcheck.run_short test (skipped without it).
# libmpfr-dev: the correctly rounded oracle of unit.math, which checks the
# engine's own elementary functions (core/math.h) to 1 ulp.
# python3-vtk9: VTK's own XML readers (the library ParaView is built on),
# with which cli.vtk_readers opens a run's frames.pvd, particle, wall and
# shape files (skipped without it); its Python modules are named vtkmodules
# (no python3-vtkmodules package exists: this is the one).
# python3-dev, python3-numpy, python3-pytest: the Python binding (python/,
# docs/python.md), built in C against Debian's interpreter and its numpy,
# and its pytest suite (the python.* tests). Two modules those tests import
# come from no package: shapedem is the project's own (built into
# build/python) and conftest is the suite's own tests/python/conftest.py.
# libcairo2-dev: `shapedem render` (src/render/) draws frames headless into
# PNG files with cairo's image surfaces (the build leaves render out without it).
# openmpi-bin, libopenmpi-dev: the MPI decomposition (shapedem-mpi, docs/mpi.md);
# libhdf5-openmpi-dev: HDF5 built with MPI-IO, with which shapedem-mpi writes
# each checkpoint from every rank into one file (without it rank 0 writes it;
# CMake takes the serial HDF5, pkg-config's hdf5-serial, for everything else).
need_pkgs=(build-essential cmake pkg-config libyaml-dev libhdf5-dev libccd-dev libqhull-dev
  python3 python3-matplotlib python3-h5py git clang libclang-rt-dev valgrind libmpfr-dev
  libcairo2-dev openmpi-bin libopenmpi-dev libhdf5-openmpi-dev
  python3-vtk9 python3-dev python3-numpy python3-pytest)
if [[ "${SHAPEDEM_WITH_BENCH:-0}" == 1 ]]; then
  need_pkgs+=(liggghts)
fi

if [[ "${1:-}" == --list ]]; then
  printf '%s\n' "${need_pkgs[@]}"
  exit 0
fi

missing=()
for p in "${need_pkgs[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

if ! command -v apt-get >/dev/null 2>&1; then
  echo "shapedem: missing packages: ${missing[*]} (no apt-get here; install them with your package manager)" >&2
  exit 1
fi

if [[ $(id -u) -eq 0 ]]; then
  echo "shapedem: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y --no-install-recommends "${missing[@]}" >/dev/null 2>&1 || {
    apt-get update >/dev/null && apt-get install -y --no-install-recommends "${missing[@]}"
  }
else
  echo "shapedem: missing packages: ${missing[*]}" >&2
  echo "run:  sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi
