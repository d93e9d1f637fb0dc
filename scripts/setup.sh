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
  libgtest-dev googletest
  graphviz clang-format
  spin                                 # cross-checks the Promela export (test/backends/checkers)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q >&2
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
