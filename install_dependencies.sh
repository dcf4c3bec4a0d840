#!/usr/bin/env bash
# Installs what drapelab needs from Debian's packages (Debian 12), skipping what is there, and
# puts analysis/ and the build's module folder build/python/ on the path of Debian's
# /usr/bin/python3 (`import drapelab` and `import drapeanalysis` anywhere, docs/python.md).
set -euo pipefail
packages=(cmake g++ make libeigen3-dev libsundials-dev nlohmann-json3-dev libgtest-dev
          libbenchmark-dev libcli11-dev libfmt-dev libtinyobjloader-dev libspectra-dev python3-matplotlib
          libsuitesparse-dev libopenblas0-serial  # UMFPACK, and a fast BLAS under it
          python3-numpy python3-pandas python3-vtk9 ffmpeg parallel libjs-three chromium libcpp-httplib-dev
          chromium-driver python3-selenium  # the live page's browser check (Selenium)
          python3-scipy  # MINPACK's fsolve for the independent DIRK reference (tests/validation)
          pybind11-dev python3-dev python3-pytest  # the Python module drapelab and its tests
          clang libclang-rt-dev  # the sanitize and fuzz presets: clang, its sanitizer and libFuzzer runtimes
          libomp-dev)  # clang's OpenMP runtime and Archer, for the tsan preset (docs/performance/threads.md)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if ((${#missing[@]})); then
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# A .pth file in the interpreter's first site directory (/usr/local/lib/python3.11/dist-packages
# on Debian 12, which pip and apt leave alone) names this checkout's analysis/ folder and the
# release build's module folder (it need not exist yet: the interpreter skips it until the
# build makes it): no pip, no network. Rerun after moving the checkout.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
site="$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')"
$sudo mkdir -p "$site"
printf '%s\n' "$root/analysis" "$root/build/python" | $sudo tee "$site/drapelab-analysis.pth" >/dev/null
