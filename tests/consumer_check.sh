#!/usr/bin/env bash
# consumer_check.sh SOURCE BUILD — the install test (CTest install_consumer):
# installs BUILD into a fresh prefix under BUILD/consumer, configures and
# builds tests/consumer against it with find_package(clraster), runs it,
# does the same against BUILD itself as the package, and imports the installed Python module with its documented PYTHONPATH.
set -euo pipefail
src="$1" build="$2"
work="$build/consumer"
prefix="$work/prefix"
rm -rf "$work"
cmake --install "$build" --prefix "$prefix" >/dev/null
for f in bin/clraster include/clraster/clraster.hpp lib/cmake/clraster/clrasterConfig.cmake \
         lib/cmake/clraster/clrasterConfigVersion.cmake; do
  [[ -e "$prefix/$f" ]] || { echo "consumer_check: $prefix/$f not installed" >&2; exit 1; }
done
cmake -S "$src/tests/consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer" "$work/out.png"
[[ -s "$work/out.png" ]] || { echo "consumer_check: no PNG written" >&2; exit 1; }
# The build tree is a package as well (clraster_DIR=BUILD).
cmake -S "$src/tests/consumer" -B "$work/build-tree" -Dclraster_DIR="$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build-tree" >/dev/null
"$work/build-tree/consumer" "$work/out-tree.png"
[[ -s "$work/out-tree.png" ]] || { echo "consumer_check: no PNG from the build-tree package" >&2; exit 1; }
PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
  "import clraster, numpy as np; print('python: clraster from', clraster.__file__)"
"$prefix/bin/clraster" devices >/dev/null
echo "consumer_check: ok"
