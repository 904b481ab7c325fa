#!/usr/bin/env bash
# Installs the Debian packages inertest builds, tests and benchmarks with.
# Skips apt entirely when everything is already present, so a second `make test` is fast.
# chromium renders the reports and the web view in the tests; fonts-wqy-microhei gives it the CJK
# glyphs of the Chinese (zh) pages and the docs/ screenshots.
set -euo pipefail

packages=(
  build-essential cmake ccache pkg-config clang libclang-rt-14-dev llvm
  libeigen3-dev libfmt-dev libcli11-dev nlohmann-json3-dev libtomlplusplus-dev libfast-float-dev
  libboost-dev
  libsqlite3-dev libpq-dev postgresql libssl-dev
  libmatio-dev libhdf5-dev zlib1g-dev
  libfftw3-dev
  libcpp-httplib-dev
  libgtest-dev googletest libbenchmark-dev
  python3-numpy python3-pandas python3-scipy python3-h5py python3-pytest python3-dev pybind11-dev
  chromium fonts-wqy-microhei
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$p")
done
((${#missing[@]} == 0)) && exit 0

sudo=()
if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
echo "install-deps: installing ${missing[*]}" >&2
# The tests start their own PostgreSQL server in a temporary directory: keep Debian's package from
# creating (and starting) its default cluster.
if [[ " ${missing[*]} " == *" postgresql "* && ! -d /var/lib/postgresql/15/main ]]; then
  "${sudo[@]}" mkdir -p /etc/postgresql-common/createcluster.d
  echo "create_main_cluster = false" | "${sudo[@]}" tee /etc/postgresql-common/createcluster.d/inertest.conf > /dev/null
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
