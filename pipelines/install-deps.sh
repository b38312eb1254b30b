#!/usr/bin/env bash
# Installs, from Debian 12 packages, everything the project builds, tests and plots with.
# Idempotent and non-interactive: packages already present are skipped by apt itself.
#   --with-lammps  also install LAMMPS (Debian's `lammps`, the `lmp` program), for
#                  `make -C pipelines bench-lammps` only; the build, the tests and CI do not need it.
#   --with-slurm   also install a single-node Slurm (slurmctld, slurmd, slurm-client, munge) for
#                  `make -C pipelines test-slurm` (ctest regression.slurm installs it this way when it
#                  is missing and it runs as root; docs/cluster.md).
set -euo pipefail

with_lammps=0
with_slurm=0
for arg in "$@"; do
  case "$arg" in
    --with-lammps) with_lammps=1 ;;
    --with-slurm) with_slurm=1 ;;
    -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps: unknown option '$arg' (known: --with-lammps, --with-slurm)" >&2; exit 2 ;;
  esac
done

packages=(
  # toolchain
  build-essential cmake pkg-config git
  # numerics and geometry
  libeigen3-dev libsuitesparse-dev libceres-dev libcgal-dev
  # an optimised BLAS for UMFPACK's dense kernels (the BLAS alternative picks it over the reference and
  # ATLAS builds; the OpenMP variant runs serially inside the ensemble's one-thread workers): 1.3x on a
  # microcell's Newton solves
  libopenblas0-openmp
  # meshing (library and the command-line mesher)
  libgmsh-dev gmsh
  # I/O, configuration, command line, logging
  libhdf5-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # figures (Debian's python3, /usr/bin/python3)
  python3 python3-matplotlib python3-numpy python3-h5py
  # uncertainty quantification: distributions, bootstrap draws (make -C pipelines uq-sdel)
  python3-openturns
  # the distributed layer: MPI (Open MPI, its mpirun for the tests) and Zoltan's partitioner
  libopenmpi-dev openmpi-bin libtrilinos-zoltan-dev
)
if [ "$with_lammps" -eq 1 ]; then
  # the speed peer of the macro benchmark: lmp (mpirun for its 2-process run is installed always)
  packages+=(lammps)
fi
if [ "$with_slurm" -eq 1 ]; then
  packages+=(slurmctld slurmd slurm-client munge)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "install-deps: done"
