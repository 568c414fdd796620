#!/usr/bin/env bash
# Installs vorogeo's build dependencies from Debian packages. Idempotent: prints
# nothing and changes nothing when everything is already present.
set -euo pipefail

# clang + libclang-rt-14-dev: libFuzzer for scripts/fuzz.sh (gcc has no coverage-guided fuzzer);
# gcc's own ASan/UBSan/TSan runtimes come with g++.
packages=(cmake g++ make libopenmesh-dev libzstd-dev libflatbuffers-dev flatbuffers-compiler
          libtbb-dev catch2 libstb-dev pkg-config mono-mcs mono-runtime python3
          clang libclang-rt-14-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
