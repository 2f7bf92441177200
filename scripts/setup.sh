#!/usr/bin/env bash
# Installs the Debian 12 packages Cupola needs, only those that are missing. Run as root
# (or with sudo available). Safe to run again.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git python3
  libglm-dev                                   # maths (GLSL-compatible types)
  libegl-dev libopengl-dev libgl-dev           # EGL + OpenGL through libglvnd
  libegl-mesa0 libgl1-mesa-dri                 # Mesa (llvmpipe) for machines without a GPU
  libopenimageio-dev openimageio-tools         # image files (EXR, PNG) and oiiotool
  libusb-1.0-0-dev libudev-dev                 # navigation devices (master)
  umockdev libumockdev-dev                     # emulated USB devices for the navigation-device tests
  nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  libvalijson-dev                              # JSON Schema validation of the configs (configs/schema/)
  libsodium-dev                                # HMAC-SHA256 packet authentication, BLAKE2b hashes
  liberfa-dev                                  # time scales and Earth rotation (ERFA)
  libnova-dev                                  # planet and Pluto series (VSOP87, Meeus ch. 37)
  libx11-dev libxrandr-dev libdrm-dev libgbm-dev # live outputs: window sink (X11, RandR), KMS sink (DRM, GBM)
  xvfb xauth                                   # a real X server for the window-sink tests
  libzip-dev libpugixml-dev                    # MPCDI calibration packages: zip container, mpcdi.xml
  python3-numpy python3-openimageio            # tools/mpcdi_reference.py, the independent MPCDI reading
  libgtest-dev libgmock-dev libbenchmark-dev   # tests and benchmarks
  xplanet-images                               # Earth texture
  openuniverse-common                          # planet, Moon and Milky Way maps (configs/scenes/solar-system.json)
  iproute2 nftables                            # multi-host cluster tests: namespaces, veth, packet loss
  clang-format universal-ctags                 # source checks in ctest: formatting, function length
  clang libclang-rt-14-dev                     # libFuzzer + ASan/UBSan runtimes for fuzz/ (clang++ only)
  dpkg-dev file systemd                        # the .deb: cpack's dpkg-shlibdeps and file; its units and user checked offline (ctest packaging_*)
  libfreetype-dev fonts-dejavu-core            # alignment pattern: channel labels (FreeType, DejaVu Sans)
  libgdal-dev                                  # terrain elevation: GeoTIFF and the rasters GDAL reads
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
