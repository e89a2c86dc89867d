#!/usr/bin/env bash
# CMAKE_CROSSCOMPILING_EMULATOR of the Windows x64 build: runs PROGRAM
# under wine64 and returns its exit status. WINEPREFIX comes from the test
# (tests/CMakeLists.txt puts it in the build folder), or defaults to one
# beside the program; the first start creates it (slow, once per prefix).
# usage: wine-run.sh PROGRAM.exe [ARGS...]
set -eu
wine=$(command -v wine64 || true)
[ -n "$wine" ] || [ ! -x /usr/lib/wine/wine64 ] || wine=/usr/lib/wine/wine64
if [ -z "$wine" ]; then
  echo "wine-run.sh: wine64 not found (Debian package wine64)" >&2
  exit 127
fi
export WINEPREFIX="${WINEPREFIX:-$(cd "$(dirname "$1")" && pwd)/wineprefix}"
export WINEDEBUG="${WINEDEBUG:--all}"
# No desktop integration or Mono/Gecko prompts in a headless CI.
export WINEDLLOVERRIDES="${WINEDLLOVERRIDES:-mscoree,mshtml=}"
exec "$wine" "$@"
