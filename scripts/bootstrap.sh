#!/usr/bin/env bash
# Installs what grip needs to build and test on Debian 12, from Debian's own packages only.
# Safe to run again: it installs only what is missing. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  ccache                 # CI's fresh clone reuses what earlier builds compiled
  help2man               # the man page grip(1), from `grip --help`
  libeigen3-dev          # fixed-size vehicle states
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev           # the grip command line
  nlohmann-json3-dev     # JSON reports (tools only, never on the planning path)
  libcairo2-dev          # PNG figures
  libyaml-cpp-dev        # ROS map_server map metadata (sim/, `--map FILE.yaml`)
  cyclonedds-dev cyclonedds-tools  # DDS: libddsc, idlc and the CMake package
  stress-ng              # the load of `grip stress --load` (a built-in load is the fallback)
  libsystemd-dev         # sd_notify: readiness and watchdog of the grip-planner service
  util-linux             # setpriv: the scheduling tests drop capabilities with it
  clang libclang-rt-14-dev  # scripts/fuzz.sh: the libFuzzer targets (tests/fuzz) and their runtime
  iproute2 iptables      # `grip bench faults`: network namespaces, a veth pair, loss and cuts
  libnetfilter-queue-dev # `grip bench faults`: its delay (the kernel here has no netem)
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev  # optional: `grip bench ompl` (OMPL 1.5 links against these Boost libraries)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "bootstrap: run as root or install sudo" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "bootstrap: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
