#!/bin/sh
# Install the Debian packages gomboc needs, only those missing. Needs root (or sudo) when
# anything is missing; does nothing, and needs no privileges, when everything is present.
#   install-deps.sh            what every build, run and verify needs
#   install-deps.sh fuzz       and clang with its libFuzzer runtime (make fuzz)
#   install-deps.sh valgrind   and valgrind (make valgrind)
#   install-deps.sh mpi        and OpenMPI (make mpi)
#   install-deps.sh siconos    and Siconos's Python modules (make references: the reference impacts)
set -eu
packages="build-essential pkg-config libgsl-dev libcunit1-dev libinih-dev libcjson-dev libqhull-dev libsodium-dev libmatheval-dev
libsiconos-numerics-dev libflint-arb-dev
python3 python3-numpy python3-cffi python3-scipy python3-sympy python3-matplotlib python3-pil groff-base"
for extra in "$@"; do
    case "$extra" in
        fuzz) packages="$packages clang libclang-rt-dev" ;;
        valgrind) packages="$packages valgrind" ;;
        mpi) packages="$packages libopenmpi-dev openmpi-bin" ;;
        siconos) packages="$packages python3-siconos" ;;
        *) echo "install-deps: unknown extra '$extra' (allowed: fuzz, valgrind, mpi, siconos)" >&2; exit 2 ;;
    esac
done
missing=""
for p in $packages; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "install-deps: installing missing Debian packages:$missing" >&2
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
        echo "install-deps: these packages are missing and this is not root:$missing" >&2
        echo "install-deps: run 'make deps' as root, or install them with apt-get" >&2
        exit 1
    fi
else SUDO=""; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
