#!/usr/bin/env bash
# Installs what netlift needs to build and test, from Debian's archive only.
# Idempotent: installs only the packages that are missing. Works as root on a
# fresh Debian 12 machine (uses sudo when not root and sudo exists).
set -euo pipefail

packages=(
  cmake g++ make ninja-build python3
  llvm-14-dev llvm-14-tools            # LLVM ADT/Support; FileCheck, not, split-file, lit
  antlr4 libantlr4-runtime-dev default-jre-headless
  libfmt-dev libpugixml-dev
  libtcmalloc-minimal4                 # the tools' allocator (CMakeLists.txt says why)
  libgtest-dev googletest
  graphviz clang-format
  dpkg-dev                             # dpkg-shlibdeps: the Debian package's dependencies (make package)
  spin                                 # cross-checks the Promela export (test/backends/checkers)
)

# Wanted but not required: without them the tests that need them are
# UNSUPPORTED (lit says which), the rest runs.
optional=(
  chromium                             # the HTML report in a browser (test/backends/structural)
  gtkwave                              # vcd2fst/fst2vcd read the VCD traces back (test/tools/netlift)
)

installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
missing_optional=()
for p in "${optional[@]}"; do
  installed "$p" || missing_optional+=("$p")
done

if [ ${#missing[@]} -eq 0 ] && [ ${#missing_optional[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]} ${missing_optional[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: need root (or sudo) to install: ${missing[*]} ${missing_optional[*]}" >&2
    [ ${#missing[@]} -eq 0 ] && exit 0
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q >&2
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
fi
for p in "${missing_optional[@]}"; do
  $SUDO apt-get install -y -q --no-install-recommends "$p" >&2 ||
    echo "setup: $p could not be installed; the tests that need it are skipped" >&2
done
