#!/usr/bin/env bash
# Install Slurm and MUNGE from Debian 12's archive (slurm 22.05, munge 0.5.15)
# when they are missing: what tools/slurm/local-slurm.sh and the integration
# test (tests/slurm) need. Installing starts no daemon of ours; the packages'
# own services stay as the system has them. Needs root (or sudo).
set -euo pipefail
packages=(slurmctld slurmd slurm-client munge)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null && sudo -n true 2>/dev/null || {
    echo "install-slurm.sh: installing ${missing[*]} needs root (or sudo without a password)" >&2
    exit 3
  }
  sudo=sudo
else
  sudo=
fi
command -v apt-get >/dev/null || { echo "install-slurm.sh: no apt-get: install ${missing[*]} with your system's tools" >&2; exit 3; }
echo "install-slurm.sh: installing ${missing[*]}" >&2
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
