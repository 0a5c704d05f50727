#!/usr/bin/env bash
# Install the Debian packages rosreconf's tests use, only those that are missing.
# Needs root (CI and the development machines run as root); otherwise prints the command.
set -euo pipefail
need=()
command -v dot >/dev/null 2>&1 || need+=(graphviz)
/usr/bin/python3 -c 'import roslaunch.xmlloader' >/dev/null 2>&1 || need+=(python3-roslaunch)
if [ ${#need[@]} -eq 0 ]; then
  echo "system-deps: all present"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "system-deps: missing ${need[*]}; run: sudo apt-get install -y ${need[*]}" >&2
  exit 1
fi
echo "system-deps: installing ${need[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
