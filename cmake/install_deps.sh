#!/usr/bin/env bash
# Installs everything rigidlab needs on Debian 12, from Debian packages only. Idempotent: when all
# packages are present it only runs `dpkg-query` and exits (well under a second).
#
# sol2 is not packaged for Debian 12, so its header-only `sol2-dev` (3.5.0, architecture `all`) is
# taken from Debian unstable: apt downloads the .deb using a throw-away source list in a temporary
# directory (nothing is added to the system's apt configuration), and dpkg installs it.
#
# Usage: cmake/install_deps.sh            (uses sudo when not run as root)
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev                       # core: all vector and matrix math
  doctest-dev                         # C++ tests
  liblua5.4-dev lua5.4                # Lua layer
  libsdl2-dev libgl-dev libimgui-dev  # sandbox (libimgui.a holds the SDL2 + OpenGL3 backends)
  libstb-dev                          # sandbox screenshots (stb_image_write), PNG checks in tests
  xvfb xauth libgl1-mesa-dri          # sandbox tests under a virtual X server, Mesa software GL
  xdotool                             # sandbox interaction test: real mouse and keys under Xvfb
  gnuplot-nox                         # accuracy-report pictures
  clang libclang-rt-14-dev            # libFuzzer targets and the sanitizer runtime (tests/fuzz)
  libxml2-utils                       # xmllint: the test of rigidlab test validates its JUnit XML (tests/runner/junit-4.xsd)
  nlohmann-json3-dev                  # the program's JSON reader (engine/app/json_value.cpp)
  g++-aarch64-linux-gnu               # compile-only check that the core builds for aarch64 (tests/portability)
)
sol2_version=3.5.0

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install_deps: run as root or install sudo" >&2; exit 1; }
  sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "install_deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  # A fresh machine may have empty package lists: try as is, update and retry once.
  if ! "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"; then
    "${sudo_cmd[@]}" apt-get update
    "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
  fi
fi

sol2_installed=$(dpkg-query -W -f='${Version}' sol2-dev 2>/dev/null || true)
if [[ "$sol2_installed" != ${sol2_version}* ]]; then
  echo "install_deps: fetching sol2-dev ${sol2_version} from Debian unstable"
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  chmod 755 "$tmp"
  mkdir -p "$tmp/lists/partial"
  echo "deb [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian sid main" \
    > "$tmp/sources.list"
  apt_opts=(-o "Dir::Etc::SourceList=$tmp/sources.list" -o Dir::Etc::SourceParts=/dev/null
            -o "Dir::State::Lists=$tmp/lists" -o Debug::NoLocking=1)
  "${sudo_cmd[@]}" apt-get "${apt_opts[@]}" update -qq
  (cd "$tmp" && "${sudo_cmd[@]}" apt-get "${apt_opts[@]}" download "sol2-dev" 2>&1 | grep -v '^W: Download is performed unsandboxed' || true)
  deb=$(ls "$tmp"/sol2-dev_*_all.deb)
  case "$(basename "$deb")" in
    sol2-dev_${sol2_version}*) ;;
    *) echo "install_deps: expected sol2-dev ${sol2_version}, got $(basename "$deb")" >&2; exit 1 ;;
  esac
  "${sudo_cmd[@]}" dpkg -i "$deb"
fi
