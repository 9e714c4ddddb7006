#!/usr/bin/env bash
# Finds the commit that broke one configuration, with `git bisect run`:
#
#   scripts/bisect.sh GOOD BAD --id ID [--image NAME | --pass P]
#                     [--matrix M] [--baselines DIR] [--frames N]
#
# Each commit is built in its own folder outside the source tree
# ($CAVITY_BISECT_WORK, default a new folder under ${TMPDIR:-/tmp}), from a
# detached worktree, so the checkout you run it from is never touched. The
# oracle (scripts/bisect_step.py) is the invoking tree's, the same at every
# step:
#   --image NAME (or neither flag): `cavity gate --filter ^ID$ --retries 0`
#       against this tree's baselines (or --baselines DIR); the commit is bad
#       when that image (or, without NAME, any check of ID) fails.
#   --pass P: `cavity run` of ID at GOOD and at the commit, judged by this
#       tree's `cavity compare` (build/harness/cavity); bad when pass P is
#       `slower` (U test, interval and --min-change, as in the README).
# A commit that does not build, or whose run gives no verdict, is skipped
# (exit 125 to git bisect). Prints the first bad commit with its numbers and
# the numbers of every commit tested. Exit 0 when found, 1 when bisect could
# not name one commit, 2 for bad arguments.
#
# Overridable (a test plugs in a fast stand-in project; on a shared machine,
# prefix the build with a lock):
#   CAVITY_BISECT_BUILD    build command, run by bash with SRC and BUILD set
#                          (default: cmake -S "$SRC" -B "$BUILD" -G Ninja
#                          -DCMAKE_BUILD_TYPE=Release && cmake --build "$BUILD")
#   CAVITY_BISECT_RUN      run command, with BUILD, OUT, ID, MATRIX, BASELINES,
#                          FRAMES set; leaves OUT/gate.json (image mode) or
#                          OUT/results.json (pass mode)
#   CAVITY_BISECT_COMPARE  the cavity that judges --pass (default this tree's build)
set -euo pipefail

usage="usage: scripts/bisect.sh GOOD BAD --id ID [--image NAME | --pass P] [--matrix M] [--baselines DIR] [--frames N]"
die() { echo "bisect.sh: $*" >&2; exit 2; }

here=$(cd "$(dirname "$0")" && pwd)
good="" bad="" id="" image="" pass="" matrix=ci baselines="" frames=30
positional=()
while [ $# -gt 0 ]; do
    case "$1" in
    --id|--image|--pass|--matrix|--baselines|--frames)
        [ $# -ge 2 ] && [ -n "$2" ] || die "$1: missing value ($usage)"
        case "$1" in
        --id) id=$2 ;; --image) image=$2 ;; --pass) pass=$2 ;;
        --matrix) matrix=$2 ;; --baselines) baselines=$2 ;; --frames) frames=$2 ;;
        esac
        shift 2 ;;
    -h|--help) echo "$usage"; exit 0 ;;
    --*) die "$1: unknown flag ($usage)" ;;
    *) positional+=("$1"); shift ;;
    esac
done
[ ${#positional[@]} -eq 2 ] || die "needs GOOD and BAD commits, got ${#positional[@]} arguments ($usage)"
good=${positional[0]} bad=${positional[1]}
[ -n "$id" ] || die "--id: missing (the configuration id, e.g. corner/alchemy/n16/b4/full/160x90/vk/compute)"
[ -z "$image" ] || [ -z "$pass" ] || die "--image $image and --pass $pass: give one oracle, not both"
[ -z "$image" ] || [[ $image =~ ^(ao|ao_blur|color)$ ]] || die "--image $image: must be ao, ao_blur or color"
[[ $frames =~ ^[0-9]+$ ]] && [ "$frames" -ge 1 ] || die "--frames $frames: must be an integer >= 1"

repo=$(git rev-parse --show-toplevel 2>/dev/null) || die "$(pwd): not inside a git repository"
good_sha=$(git -C "$repo" rev-parse --verify --quiet "$good^{commit}") || die "GOOD $good: not a commit of $repo"
bad_sha=$(git -C "$repo" rev-parse --verify --quiet "$bad^{commit}") || die "BAD $bad: not a commit of $repo"
git -C "$repo" merge-base --is-ancestor "$good_sha" "$bad_sha" || die "GOOD $good is not an ancestor of BAD $bad"
[ -n "$baselines" ] || baselines="$repo/baselines"
baselines=$(cd "$baselines" 2>/dev/null && pwd) || die "--baselines $baselines: not a folder"

work=${CAVITY_BISECT_WORK:-$(mktemp -d "${TMPDIR:-/tmp}/cavity-bisect.XXXXXX")}
mkdir -p "$work/driver" "$work/numbers"
# The oracle stays this tree's while bisect checks out older ones.
cp "$here/bisect_step.py" "$work/driver/"
export CAVITY_BISECT_WORK=$work CAVITY_BISECT_ID=$id CAVITY_BISECT_IMAGE=$image CAVITY_BISECT_PASS=$pass
export CAVITY_BISECT_MATRIX=$matrix CAVITY_BISECT_BASELINES=$baselines CAVITY_BISECT_FRAMES=$frames
export CAVITY_BISECT_COMPARE=${CAVITY_BISECT_COMPARE:-$repo/build/harness/cavity}

src="$work/src"
git -C "$repo" worktree add --quiet --detach "$src" "$bad_sha"
cleanup() {
    git -C "$src" bisect reset --quiet >/dev/null 2>&1 || true
    git -C "$repo" worktree remove --force "$src" >/dev/null 2>&1 || true
}
trap cleanup EXIT

if [ -n "$pass" ]; then
    # The reference the commits are compared with: GOOD's own run.
    git -C "$src" checkout --quiet --detach "$good_sha"
    (cd "$src" && CAVITY_BISECT_REFERENCE=1 python3 "$work/driver/bisect_step.py") ||
        { echo "bisect.sh: GOOD $good does not build or run; no reference for --pass $pass" >&2; exit 1; }
fi

cd "$src"
git bisect start "$bad_sha" "$good_sha" >/dev/null
git bisect run python3 "$work/driver/bisect_step.py" >"$work/bisect.log" 2>&1 || true
first=$(sed -n 's/^\([0-9a-f]\{40\}\) is the first bad commit$/\1/p' "$work/bisect.log" | head -n 1)

echo "commits tested, in order (work folder $work):"
[ -f "$work/tested.txt" ] && sed 's/^/  /' "$work/tested.txt"
if [ -z "$first" ]; then
    echo "bisect.sh: no single first bad commit; git bisect said:" >&2
    tail -n 15 "$work/bisect.log" >&2
    exit 1
fi
echo "first bad commit: $(git -C "$repo" log -1 --format='%H %s' "$first")"
[ -f "$work/numbers/$first.txt" ] && sed 's/^/  /' "$work/numbers/$first.txt"
exit 0
