#!/usr/bin/env bash
# tools/run.sh fresh [JOB [ARGS]]: run `tools/run.sh JOB ARGS` (JOB: test
# unless named) in a clean minimal Debian root, as a new user's fresh
# machine would: only Debian's essential packages and apt, so that every
# package the job needs must come from tools/packages.txt. See
# docs/TESTING.md, "A clean Debian root".
#
#   1. The root: `mmdebstrap --variant=apt SUITE` from the host's apt
#      sources (suite and mirrors as the host has them), kept as
#      $FRESH_DIR/debian-SUITE.tar and reused; delete it to make a new one.
#   2. Each run extracts that tarball into a new folder
#      ($FRESH_DIR/root-DATE-TIME), copies in the host's apt sources, the
#      host's archive access settings and /etc/resolv.conf, and clones the
#      current commit (HEAD, not the working tree: no build folders, no
#      uncommitted changes) to /work/shadowvol, with the host's ../shared
#      bind-mounted read-only at /work/shared so that ../shared resolves.
#   3. It chroots in with /proc, /dev and /sys mounted and runs
#      `cd /work/shadowvol && tools/run.sh JOB ARGS` as root, with a bare
#      environment and no terminal, as a CI runner would.
#
# Every mount is made in a private mount namespace (unshare): the host never
# sees them, they vanish with the namespace even when this script is killed,
# and removing a root folder can never reach the host's /dev or ../shared
# through a leftover bind mount. The root folder is still removed only after
# findmnt shows nothing mounted under it.
#
# FRESH_DIR (default: build-fresh, git-ignored) holds the tarball, the roots
# and the logs; FRESH_KEEP=1 keeps the run's root for inspection (it takes
# several GB after the test job). One run per FRESH_DIR at a time (a lock).
# Prints each phase's seconds and each ctest run's summary; the full log,
# each line prefixed with the seconds since the job started, is
# $FRESH_DIR/fresh-DATE-TIME.log. Exits with the job's status.
set -euo pipefail

die() { echo "tools/run.sh fresh: $*" >&2; exit 2; }
say() { echo "tools/run.sh fresh: $*" >&2; }

# ---- inside the private mount namespace (called by the outer part below) ----
if [ "${1:-}" = --in-namespace ]; then
  shift
  root="$1" shared="$2" inner_cmd="$3"
  mounted=()
  # Unmounts in reverse order, each recursively (/dev and /sys are recursive
  # binds); a busy mount is detached lazily, which is safe here because the
  # namespace is private. Fails when anything is still mounted under root.
  unmount_all() {
    local i
    for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
      umount -R "${mounted[i]}" 2>/dev/null || umount -R -l "${mounted[i]}" || true
    done
    mounted=()
    if findmnt -rn -o TARGET | grep -q -F -- "$root/"; then
      echo "tools/run.sh fresh: still mounted under $root:" >&2
      findmnt -rn -o TARGET | grep -F -- "$root/" >&2
      return 1
    fi
  }
  # Processes the job left behind in the root (wineserver outlives wine by
  # a few seconds, a hung test outlives a killed ctest) hold its mounts
  # busy: end them, by id, before unmounting.
  end_leftovers() {
    local sig pid pids
    for sig in TERM KILL; do
      pids=()
      for pid in /proc/[0-9]*; do
        pid="${pid#/proc/}"
        [ "$(readlink "/proc/$pid/root" 2>/dev/null)" = "$root" ] && pids+=("$pid")
      done
      [ ${#pids[@]} -eq 0 ] && return 0
      echo "tools/run.sh fresh: ending ${#pids[@]} process(es) left in the root (SIG$sig)" >&2
      kill -s "$sig" "${pids[@]}" 2>/dev/null || true
      sleep 2
    done
  }
  trap 'end_leftovers; unmount_all' EXIT
  # A signal (the outer part forwards its own) exits through the EXIT
  # trap's cleanup; set before anything is mounted or started.
  trap 'exit 129' HUP; trap 'exit 130' INT; trap 'exit 143' TERM
  # /dev and /sys with what is mounted under them (/dev/pts, /dev/shm),
  # made slaves: the namespace is private already, and nothing mounted or
  # unmounted in the root could propagate back to the host's even without it.
  mount -t proc proc "$root/proc"; mounted+=("$root/proc")
  mount --rbind /dev "$root/dev"; mount --make-rslave "$root/dev"; mounted+=("$root/dev")
  mount --rbind /sys "$root/sys"; mount --make-rslave "$root/sys"; mounted+=("$root/sys")
  if [ -n "$shared" ]; then
    mount --bind "$shared" "$root/work/shared"; mounted+=("$root/work/shared")
    mount -o remount,bind,ro "$root/work/shared"
  fi
  # A CI runner's environment: no terminal (stdin from /dev/null, output to
  # a pipe), root, the default PATH, CI set; nothing of this shell's
  # environment leaks in (env -i). In the background and waited for: bash
  # runs a trap only once the foreground command ends, and a signal must
  # end the job at once.
  env -i HOME=/root USER=root LOGNAME=root SHELL=/bin/bash CI=true \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    chroot "$root" /bin/bash -lc "$inner_cmd" </dev/null 2>&1 &
  status=0
  wait $! || status=$?
  end_leftovers
  unmount_all || exit 3
  trap - EXIT
  exit $status
fi

# ---- outside ----
# One block, which bash reads whole before running it: a checkout or an
# edit of this file during a long run cannot change what the run does.
{
cd "$(dirname "$0")/.."
repo="$PWD"

job="${1:-test}"
[ $# -gt 0 ] && shift
case "$job" in
  bench|test|fuzz|cross|lint) ;;
  fresh) die "JOB cannot be fresh itself" ;;
  *) die "unknown JOB '$job' (one of: bench test fuzz cross lint)" ;;
esac
[ "$(id -u)" -eq 0 ] || die "needs root (mmdebstrap's root mode, chroot, mounts): run it as root or with sudo"
for c in mmdebstrap unshare chroot findmnt flock git tar apt-config; do
  command -v "$c" >/dev/null 2>&1 || die "needs $c (tools/run.sh fresh installs mmdebstrap; the rest are in util-linux, coreutils, git, tar, apt)"
done

fresh_dir="${FRESH_DIR:-build-fresh}"
mkdir -p "$fresh_dir"
fresh_dir="$(cd "$fresh_dir" && pwd)"
case "$fresh_dir" in /|/dev|/dev/*|/proc|/proc/*|/sys|/sys/*) die "FRESH_DIR=$fresh_dir is not a place for roots" ;; esac
# The job inherits the lock: if this script is killed outright (SIGKILL),
# its job, still running in the root, keeps it until it ends.
exec 9>"$fresh_dir/lock"
flock -n 9 || die "another fresh run holds $fresh_dir/lock"

t_all=$SECONDS
phase_times=()
phase() { phase_times+=("$(printf '%-40s %6d s' "$1" "$2")"); say "$1: $2 s"; }

# The host's apt sources: the files apt itself reads (sources.list and
# sources.list.d/*.list, *.sources; other names there are ignored by apt).
sources=()
if [ -f /etc/apt/sources.list ] && grep -q '^[[:space:]]*deb[[:space:]]' /etc/apt/sources.list; then
  sources+=(/etc/apt/sources.list)
fi
for f in /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
  [ -f "$f" ] && sources+=("$f")
done
[ ${#sources[@]} -gt 0 ] || die "no apt sources on this machine (/etc/apt/sources.list, /etc/apt/sources.list.d/) to make the root from"
# The suite: the first binary entry's first suite without a dash (bookworm,
# not bookworm-updates or bookworm-security), in either format.
suite="$(awk '
  FNR == 1 { deb822 = (FILENAME ~ /\.sources$/); types = "" }
  deb822 && tolower($1) == "types:" { types = $0 }
  deb822 && tolower($1) == "suites:" && types ~ /[[:space:]]deb([[:space:]]|$)/ {
    for (i = 2; i <= NF; i++) if ($i !~ /-/) { print $i; exit } }
  !deb822 && $1 == "deb" {
    i = 2; if ($i ~ /^\[/) while ($i !~ /\]$/) i++
    if ($i ~ /^\[/ || $i ~ /\]$/) i++
    i++; if ($i !~ /-/) { print $i; exit } }' "${sources[@]}")"
[ -n "$suite" ] || die "found no suite in ${sources[*]}"
case "$suite" in *[!a-z0-9]*) die "suite '$suite' read from the apt sources is not a plain release name" ;; esac

# How the host reaches the archive: validity checks (a snapshot mirror
# serves Release files past their Valid-Until) and proxies. The root needs
# them to reach the same archive, in mmdebstrap and in the job's apt-get.
access="$fresh_dir/apt-host-access.conf"
apt-config dump | grep -E '^Acquire::(Check-Valid-Until|Check-Date|(http|https|ftp)::Proxy)' >"$access" || true

tarball="$fresh_dir/debian-$suite.tar"
if [ ! -f "$tarball" ]; then
  say "making the root: mmdebstrap --variant=apt $suite from ${sources[*]}"
  t0=$SECONDS
  # Written under another name and renamed when complete: an interrupted
  # mmdebstrap never leaves a tarball that later runs would take as good.
  rm -f "$tarball.part"
  mmdebstrap --quiet --variant=apt --format=tar --aptopt="$access" \
    "$suite" "$tarball.part" "${sources[@]}" >"$fresh_dir/mmdebstrap.log" 2>&1 \
    || { tail -20 "$fresh_dir/mmdebstrap.log" >&2; die "mmdebstrap failed (log: $fresh_dir/mmdebstrap.log)"; }
  mv "$tarball.part" "$tarball"
  phase "make the root (mmdebstrap)" $((SECONDS - t0))
else
  say "reusing $tarball (delete it to make a new root)"
fi

# Roots of earlier runs that were killed before removing theirs (the lock
# says no run is using them): removed when nothing is mounted under them.
remove_root() {
  if findmnt -rn -o TARGET | grep -q -F -- "$1/"; then
    say "NOT removing $1: something is still mounted under it:"
    findmnt -rn -o TARGET | grep -F -- "$1/" >&2
    return 1
  fi
  rm -rf --one-file-system -- "$1"
}
rm -f "$fresh_dir"/.output-*
for old in "$fresh_dir"/root-*; do
  [ -d "$old" ] || continue
  [ "${FRESH_KEEP:-0}" = 1 ] && continue
  say "removing an earlier run's root $old"
  remove_root "$old" || die "clean up $old by hand first"
done

stamp="$(date +%Y%m%d-%H%M%S)"
root="$fresh_dir/root-$stamp"
log="$fresh_dir/fresh-$stamp.log"
t0=$SECONDS
mkdir "$root"
tar -xf "$tarball" -C "$root" --numeric-owner --same-permissions
# The host's sources replace the ones mmdebstrap wrote (the same entries,
# but byte for byte the host's), with the keyrings they name that the root
# lacks; then the archive access settings and the resolver.
rm -f "$root/etc/apt/sources.list" "$root"/etc/apt/sources.list.d/*
for f in "${sources[@]}"; do cp "$f" "$root$f"; done
sed -n 's/^[[:space:]]*Signed-By:[[:space:]]*\(\/[^[:space:]]*\).*/\1/p; s/.*signed-by=\(\/[^] ]*\).*/\1/p' "${sources[@]}" \
  | sort -u | while IFS= read -r k; do
    if [ -f "$k" ] && [ ! -e "$root$k" ]; then mkdir -p "$(dirname "$root$k")"; cp "$k" "$root$k"; fi
  done
cp "$access" "$root/etc/apt/apt.conf.d/99fresh-host-access"
cp -L --remove-destination /etc/resolv.conf "$root/etc/resolv.conf"
phase "extract the root" $((SECONDS - t0))

t0=$SECONDS
sha="$(git rev-parse HEAD)"
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then
  say "NOTE: uncommitted changes are not in the root; it tests commit $sha"
fi
mkdir -p "$root/work"
git clone -q --no-hardlinks "$repo" "$root/work/shadowvol"
git -C "$root/work/shadowvol" checkout -q --detach "$sha"
shared=""
if [ -d "$repo/../shared" ]; then
  shared="$(cd "$repo/../shared" && pwd)"
  mkdir -p "$root/work/shared"
else
  say "NOTE: no ../shared beside the repository; the tests that read it will say so"
fi
phase "clone HEAD ($(git rev-parse --short HEAD))" $((SECONDS - t0))

inner="cd /work/shadowvol && tools/run.sh $job"
for a in "$@"; do inner+=" $(printf '%q' "$a")"; done
say "running '$inner' in $root (log: $log)"

# Each line of the job's output, with the seconds since the job started, to
# the log; the phases it enters (apt, build, ctest) announced here as they
# begin.
stamp_lines() {
  local t0=$SECONDS line builds=0 tests=0 in_build=0
  while IFS= read -r line || [ -n "$line" ]; do
    printf '%6d %s\n' $((SECONDS - t0)) "$line"
    case "$line" in
      "tools/run.sh: installing "*) say "[$((SECONDS - t0)) s] apt-get installs ${line#tools/run.sh: installing }" ;;
      "["[0-9]*/[0-9]*"] "*) [ $in_build = 1 ] || { in_build=1; builds=$((builds + 1)); say "[$((SECONDS - t0)) s] build $builds started"; } ;;
      "Test project "*) in_build=0; tests=$((tests + 1)); say "[$((SECONDS - t0)) s] ctest run $tests started (${line#Test project })" ;;
      *"tests passed, "*) say "[$((SECONDS - t0)) s] ${line}" ;;
    esac
  done
}
t0=$SECONDS
# The job and the log writer in the background, joined by a FIFO, so that
# an interrupt (Ctrl-C, kill) reaches this shell's trap during the wait and
# is passed on to the namespace's shell, which ends the job's processes and
# unmounts before exiting; the root is then removed below as usual.
fifo="$fresh_dir/.output-$stamp"
mkfifo "$fifo"
stamp_lines <"$fifo" >"$log" &
stamp_pid=$!
unshare --mount --propagation private -- "$repo/tools/fresh_root.sh" --in-namespace "$root" "$shared" "$inner" \
  >"$fifo" 2>&1 </dev/null &
job_pid=$!
interrupted=""
# shellcheck disable=SC2317  # called by the traps below
forward() { interrupted="$1"; say "interrupted ($1): ending the job"; kill -s TERM "$job_pid" 2>/dev/null || true; }
trap 'forward HUP' HUP; trap 'forward INT' INT; trap 'forward TERM' TERM
status=0
# wait returns early (above 128) when a trap ran; wait again while the job
# is still cleaning up.
until wait "$job_pid"; do
  status=$?
  kill -0 "$job_pid" 2>/dev/null || break
done
trap - HUP INT TERM
wait "$stamp_pid" || true
rm -f "$fifo"
inside=$((SECONDS - t0))

# The phases inside, from the log's timestamps: apt-get (the installer's
# announcement to its last dpkg line), each CMake configure (hidden by
# run.sh: the gap before its build's first ninja line), each build (to
# ctest's start) and each ctest run (to its "Total Test time").
inside_phases="$(awk '
  { t = $1 + 0; sub(/^ *[0-9]+ /, ""); line = $0 }
  line ~ /^tools\/run.sh: installing / && apt0 == "" { apt0 = t }
  apt0 != "" && nb == 0 && line ~ /^(Setting up|Processing triggers for|Unpacking|Selecting previously) / { aptend = t }
  line ~ /^\[[0-9]+\/[0-9]+\] / && !inb { inb = 1; nb++; bs[nb] = t; be[nb] = ""; bprev[nb] = (nb == 1 ? (aptend != "" ? aptend : 0) : ce[nc]) }
  line ~ /^\[[0-9]+\/[0-9]+\] / { be[nb] = t }
  line ~ /^Test project / { inb = 0; nc++; cs[nc] = t; ce[nc] = ""; cb[nc] = nb; if (nb) be[nb] = t }
  line ~ /Total Test time/ { ce[nc] = t }
  { last = t }
  END {
    if (apt0 != "") printf "%-38s %6d s\n", "apt-get update + install", (aptend != "" ? aptend : last) - apt0
    for (b = 1; b <= nb; b++) {
      printf "%-38s %6d s\n", "configure " b " (cmake, output hidden)", bs[b] - bprev[b]
      printf "%-38s %6d s\n", "build " b, be[b] - bs[b]
      for (c = 1; c <= nc; c++) if (cb[c] == b)
        printf "%-38s %6d s%s\n", "ctest run " c " (build " b ")", (ce[c] != "" ? ce[c] : last) - cs[c], (ce[c] != "" ? "" : " (did not finish)")
    }
  }' "$log")"

# Each ctest run's summary: its pass line, its time, and the entries that
# failed or did not run (a skip is such an entry).
echo
echo "== ctest summaries =="
awk '
  { sub(/^ *[0-9]+ /, "") }
  /^Test project / { if (n && !done) print "(did not finish)"; n++; done = 0; print "-- ctest run " n ": " $0; list = 0; next }
  /tests passed, [0-9]+ tests? failed out of/ { print; next }
  /^Total Test time/ { print; done = 1; next }
  /^The following tests (did not run|FAILED):/ { print; list = 1; next }
  list && /^[[:space:]]+[0-9]+ - / { print; next }
  { list = 0 }
  END { if (n && !done) print "(did not finish)" }' "$log"
if ! grep -q '^ *[0-9]* Test project ' "$log"; then
  echo "(no ctest run; the end of the log:)"
  tail -15 "$log"
fi

t0=$SECONDS
if [ "${FRESH_KEEP:-0}" = 1 ]; then
  say "kept the root $root (FRESH_KEEP=1): nothing is mounted in it"
else
  remove_root "$root" || status=3
fi
removed=$((SECONDS - t0))

echo
echo "== tools/run.sh fresh $job: phases (seconds) =="
printf '%s\n' "${phase_times[@]}"
[ -z "$inside_phases" ] || printf '%s\n' "$inside_phases" | sed 's/^/  /'
printf '%-40s %6d s\n' "the job in the root, in all" "$inside"
[ "${FRESH_KEEP:-0}" = 1 ] || printf '%-40s %6d s\n' "remove the root" "$removed"
printf '%-40s %6d s\n' "tools/run.sh fresh $job, in all" $((SECONDS - t_all))
echo "log: $log (exit $status${interrupted:+, interrupted by SIG$interrupted})"
exit "$status"
}
