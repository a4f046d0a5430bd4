#!/usr/bin/env bash
# Builds the peer co-simulation master for tools/bench-peer.sh, outside mechsim's build and CI:
# FMI Library 2.3, libcosim 0.11.2 (Open Simulation Platform), cosim-cli 0.11.3 and
# tools/peer/cosim_timing.cpp (cosim-cli prints no timing; this times
# execution::simulate_until), all from their public sources, without conan, against Debian's
# Boost, libzip, xerces-c, ms-gsl, yaml-cpp, fmt and libcbor.
#
#   tools/build-peer-libcosim.sh [PREFIX]
#     PREFIX   where it installs (default /work/peers if /work is writable, else
#              $HOME/.cache/mechsim-peers); the timing program lands in PREFIX/bin/cosim_timing
#   Sources: git directories (bare clones) of the three repositories, given as
#     LIBCOSIM_GIT=... COSIM_CLI_GIT=... FMILIB_GIT=... tools/build-peer-libcosim.sh
#   or found under /work/.mirror/<owner>+<name>/repo (where the search tool's `fetch` puts
#   github:open-simulation-platform/libcosim, github:open-simulation-platform/cosim-cli and
#   github:modelon-community/fmi-library), or cloned from GitHub when neither is there.
#   WITH_CLI=0 skips cosim-cli (the benchmark needs only cosim_timing).
# About 8 minutes on 2 cores, most of it libcosim. Missing Debian packages are installed with
# apt-get (sudo when not root). Nothing here is committed to mechsim but this script and the
# timing program's source.
set -euo pipefail
repo_root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -ge 1 ]; then prefix=$1
elif [ -w /work ]; then prefix=/work/peers
else prefix=$HOME/.cache/mechsim-peers; fi
mkdir -p "$prefix"
prefix=$(cd "$prefix" && pwd)
src=$prefix/src
mkdir -p "$src"
jobs=$(nproc)

# The versions checked in docs/performance.md "Against a peer: libcosim".
fmilib_ref=2.3
libcosim_ref=52cc8251   # v0.11.2
cosim_cli_ref=10c60db   # v0.11.3

packages=(cmake g++ libboost-all-dev libzip-dev libxerces-c-dev libmsgsl-dev libyaml-cpp-dev libfmt-dev libcbor-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "build-peer-libcosim: installing ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get install -y "${missing[@]}"
fi

# Exports REF of the git directory (or a fresh clone of URL) into DEST.
export_source() {  # GIT_DIR_OR_EMPTY MIRROR_NAME URL REF DEST
  local git_dir=$1 mirror=/work/.mirror/$2/repo url=$3 ref=$4 dest=$5
  if [ -f "$dest/.exported-$ref" ]; then return; fi
  if [ -z "$git_dir" ] && [ -d "$mirror" ]; then git_dir=$mirror; fi
  if [ -z "$git_dir" ]; then
    git_dir=$src/$(basename "$url").git
    [ -d "$git_dir" ] || git clone --bare "$url" "$git_dir"
  fi
  rm -rf "$dest" && mkdir -p "$dest"
  git --git-dir="$git_dir" archive "$ref" | tar -x -C "$dest"
  touch "$dest/.exported-$ref"
}
export_source "${FMILIB_GIT:-}" modelon-community+fmi-library \
  https://github.com/modelon-community/fmi-library "$fmilib_ref" "$src/fmi-library"
export_source "${LIBCOSIM_GIT:-}" open-simulation-platform+libcosim \
  https://github.com/open-simulation-platform/libcosim "$libcosim_ref" "$src/libcosim"
if [ "${WITH_CLI:-1}" != 0 ]; then
  export_source "${COSIM_CLI_GIT:-}" open-simulation-platform+cosim-cli \
    https://github.com/open-simulation-platform/cosim-cli "$cosim_cli_ref" "$src/cosim-cli"
fi

# FMI Library installs itself into FMILIB_INSTALL_PREFIX (its own convention).
if [ ! -f "$prefix/lib/libfmilib_shared.so" ]; then
  cmake -S "$src/fmi-library" -B "$src/fmi-library-build" -DCMAKE_BUILD_TYPE=Release \
    -DFMILIB_INSTALL_PREFIX="$prefix" -DFMILIB_BUILD_TESTS=OFF -DFMILIB_GENERATE_DOXYGEN_DOC=OFF
  cmake --build "$src/fmi-library-build" -j"$jobs" --target install
fi

# Debian's libzip-config.cmake checks that the libzip-tools executables exist (zipcmp ...),
# which libzip-dev does not pull in; without them a stand-in config names the library alone.
libzip_config=()
if [ ! -x /usr/bin/zipcmp ]; then
  mkdir -p "$prefix/cmake-shims/libzip"
  libzip_so=$(ls /usr/lib/*/libzip.so | head -1)
  cat > "$prefix/cmake-shims/libzip/libzip-config.cmake" <<CONFIG
# Written by tools/build-peer-libcosim.sh: libzip::zip without Debian's check for libzip-tools.
if(NOT TARGET libzip::zip)
  add_library(libzip::zip SHARED IMPORTED)
  set_target_properties(libzip::zip PROPERTIES IMPORTED_LOCATION "$libzip_so" INTERFACE_INCLUDE_DIRECTORIES /usr/include)
endif()
set(libzip_FOUND TRUE)
CONFIG
  libzip_config=(-Dlibzip_DIR="$prefix/cmake-shims/libzip")
fi

if [ ! -f "$prefix/lib/libcosim.so" ]; then
  FMILibrary_DIR=$prefix cmake "${libzip_config[@]}" -S "$src/libcosim" -B "$src/libcosim-build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_PREFIX_PATH="$prefix" \
    -DLIBCOSIM_WITH_PROXYFMU=OFF -DLIBCOSIM_BUILD_TESTS=OFF -DLIBCOSIM_BUILD_APIDOC=OFF \
    -DCMAKE_INSTALL_RPATH="$prefix/lib"
  cmake --build "$src/libcosim-build" -j"$jobs" --target install
fi

if [ "${WITH_CLI:-1}" != 0 ] && [ ! -x "$prefix/bin/cosim" ]; then
  FMILibrary_DIR=$prefix cmake "${libzip_config[@]}" -S "$src/cosim-cli" -B "$src/cosim-cli-build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_MODULE_PATH="$src/libcosim/cmake" -DCMAKE_INSTALL_RPATH="$prefix/lib"
  cmake --build "$src/cosim-cli-build" -j"$jobs" --target install
fi

# The timing program: Boost.Log is a shared library here (BOOST_LOG_DYN_LINK), and the rpath
# without new dtags lets libcosim.so find libfmilib_shared.so too.
mkdir -p "$prefix/bin"
g++ -std=c++17 -O2 -DBOOST_LOG_DYN_LINK -I"$prefix/include" \
  "$repo_root/tools/peer/cosim_timing.cpp" -o "$prefix/bin/cosim_timing" \
  -L"$prefix/lib" -lcosim -lboost_log -lboost_log_setup -lboost_thread -lpthread \
  -Wl,--disable-new-dtags,-rpath,"$prefix/lib"
echo "build-peer-libcosim: $prefix/bin/cosim_timing ready"
