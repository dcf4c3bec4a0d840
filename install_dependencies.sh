#!/usr/bin/env bash
# Installs what drapelab needs from Debian's packages (Debian 12), skipping what is there.
set -euo pipefail
packages=(cmake g++ make libeigen3-dev libsundials-dev nlohmann-json3-dev libgtest-dev
          libbenchmark-dev libcli11-dev libfmt-dev libtinyobjloader-dev python3-matplotlib
          python3-numpy parallel libjs-three chromium
          libcpp-httplib-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
