#!/usr/bin/env bash
# Checkpoint compatibility through the CLI (issue 26; the library's cases are
# in tests/test_checkpoint_compat.c): the run kept in tests/data/checkpoint-0.1.0
# (config.ini and checkpoint.bin of granflow 0.1.0, the issue's TINY silo at
# t = 3) resumes; checkpoints of this version whose stored configuration lacks
# keys at the end or in the middle resume, one that lacks a key off its default
# or holds a key this version does not know is refused naming it; none crashes.
# If a deliberate change of the checkpoint format makes the kept one
# unreadable, its resume must be refused with a message: change the first
# case to expect that, and keep the file.
NAME=checkpoint_compat
source "$(dirname "$0")/lib.bash" "$@"
TINY=(--set container.width=12 --set container.depth=6 --set container.orifice_diameter=4
      --set packing.particles=1500 --set run.duration=3 --set run.threads=1)

# The kept checkpoint of 0.1.0, resumed to t = 4.
cp -r "$DATA/checkpoint-0.1.0" K
gf run -q --resume K --set run.duration=4
expect_rc 0 "resume of tests/data/checkpoint-0.1.0"
grep -q '"status": "complete"' K/summary.json || fail "K/summary.json is not complete: $(cat K/summary.json)"
grep -q '"simulated_time": 4' K/summary.json || fail "the resumed run did not reach t = 4: $(cat K/summary.json)"
[ -e K/snapshots/snap_000002.dump ] || fail "the resumed run wrote no snapshot at t = 4"
ok "the checkpoint of granflow 0.1.0 kept in tests/data resumes to t = 4"

# older CKPT OUT WHERE [EXTRA]: CKPT with its stored configuration made older
# (settings removed at the end, in the middle or at the start, with their
# comment lines) or newer (EXTRA appended), size and CRC-32 redone, as OUT.
older() {
    python3 - "$@" <<'PY'
import re, struct, sys, zlib
src, dst, where = sys.argv[1:4]
extra = sys.argv[4] if len(sys.argv) > 4 else ""
d = open(src, "rb").read()
head = 28
plen = struct.unpack("<Q", d[head:head + 8])[0]
lines = d[head + 8:head + 8 + plen].decode().split("\n")
keys = [i for i, l in enumerate(lines) if re.match(r"^[a-z_0-9]+ =", l)]
drop = {"end": keys[-3:], "middle": keys[len(keys) // 2:len(keys) // 2 + 2], "start": keys[:2], "none": []}[where]
drop = set(drop) | {i - 1 for i in drop if lines[i - 1].startswith(";")}
text = ("\n".join(l for i, l in enumerate(lines) if i not in drop) + extra).encode()
payload = struct.pack("<Q", len(text)) + text + d[head + 8 + plen:]
open(dst, "wb").write(d[:16] + struct.pack("<Q", len(payload)) + struct.pack("<I", zlib.crc32(payload)) + payload)
PY
}

gf run -q "${TINY[@]}" -o T
expect_rc 0 "TINY run to t = 3"
for where in end middle; do
    rm -rf "$where"
    cp -r T "$where"
    older T/checkpoint.bin "$where/checkpoint.bin" "$where" || fail "cannot rewrite the checkpoint"
    gf run -q --resume "$where" --set run.duration=4
    expect_rc 0 "resume of a checkpoint whose stored configuration lacks keys at the $where"
    ok "a checkpoint without keys at the $where of its stored configuration (at their defaults) resumes"
done

# keys at the start: container.width is 12 here, the older version ran 50
cp -r T start
older T/checkpoint.bin start/checkpoint.bin start
gf run -q --resume start --set run.duration=4
expect_rc 2 "resume of a checkpoint without container.width"
expect_err "container.width differs from the configuration the checkpoint was made with: the checkpoint does not list it" \
    "a missing key off its default"
expect_err "ran at the default, 50), and here it is 12" "a missing key off its default"
ok "a checkpoint without container.width (12 here, 50 by default) is refused, naming the key and both values"

cp -r T newer
older T/checkpoint.bin newer/checkpoint.bin none "future_key = 3"$'\n'
gf run -q --resume newer --set run.duration=4
expect_rc 2 "resume of a checkpoint with a key this version does not know"
expect_err "has the key dem.future_key, which this granflow does not know" "an unknown key"
ok "a checkpoint holding a key this version does not know is refused, naming it"
echo "cli $NAME: $PASS passed"
