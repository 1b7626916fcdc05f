#!/usr/bin/env bash
# Sharded bakes through the real prt-bake (docs/scale-out.md): every plan merges to the
# one-machine bake's exact bytes, and merge names a missing, damaged or foreign shard.
# Usage: shard_cli_test.sh CASE PRT_BAKE WORK_DIR [ASSIMP_MODELS_DIR]
set -euo pipefail
case_name=$1 bake=$2 work=$3 models=${4:-/usr/share/assimp/models}
rm -rf "$work" && mkdir -p "$work" && cd "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }
# Small enough for seconds on two cores, with two bounces so every pass kind runs.
small=(--order 3 --samples 64 --bounces 2 --quiet)
# Every command has a time limit: a hung bake fails the test instead of stalling CI.
run() { timeout 300 "$bake" "$@"; }

# Runs every pass of PLAN (shards from the plan's --json) then the asset merge to OUT.
bake_all() {
  local plan=$1 out=$2 shards=$3 passes=$4
  for ((k = 0; k < passes; k++)); do
    for ((i = 0; i < shards; i++)); do run bake-shard --plan "$plan" --shard "$i" --pass "$k" --quiet; done
    run merge --plan "$plan" --pass "$k" --quiet
  done
  run merge --plan "$plan" -o "$out" --quiet
}

# flip_byte FILE OFFSET: replaces the byte at OFFSET with its complement (always a change).
flip_byte() {
  local b
  b=$(od -An -tu1 -j "$2" -N1 "$1" | tr -d ' ')
  printf "\\x$(printf %02x $((255 - b)))" | dd of="$1" bs=1 seek="$2" conv=notrunc status=none
}

# plan ... --json prints {"passes": P, ...}; prints P.
plan_passes() { sed -n 's/.*"passes": \([0-9]*\).*/\1/p'; }

# expect_failure STATUS PATTERN CMD...: CMD exits with STATUS and its stderr matches PATTERN.
expect_failure() {
  local want=$1 pattern=$2 status=0
  shift 2
  timeout 300 "$@" 2> err.txt || status=$?
  [[ $status == "$want" ]] || { cat err.txt >&2; fail "'$*' exited $status, expected $want"; }
  grep -qE -- "$pattern" err.txt || { cat err.txt >&2; fail "'$*': stderr does not match '$pattern'"; }
}

# identical_to_one_machine "OPTIONS" SHARDS...: for each shard count, plan, bake and merge
# every pass, and compare with the one-machine bake of OPTIONS byte for byte.
identical_to_one_machine() {
  local options=$1 shards passes
  shift
  read -ra opts <<< "$options"
  run --default -o one.prt "${opts[@]}"
  for shards in "$@"; do
    passes=$(run plan --default -o room.plan --shards "$shards" "${opts[@]}" --json | plan_passes)
    [[ -n $passes ]] || fail "plan --json printed no passes"
    bake_all room.plan sharded.prt "$shards" "$passes"
    cmp one.prt sharded.prt || fail "options '$options', $shards shards: the merged asset differs from the one-machine bake"
    if [[ $options == *--bounce-threshold* ]]; then
      [[ $passes == 9 && -e room.plan.pass3.merged && ! -e room.plan.pass4.merged && ! -e room.plan.pass4.shard0 ]] ||
        fail "the threshold bake did not end after bounce 3 of $passes planned passes"
    fi
    rm -f room.plan*
    echo "ok: $options, $shards shards: identical"
  done
}

case_identical() {
  # Exact bounce counts; the threshold rule (0.05 stops the room's series after 3 of the 8
  # planned bounces, so passes 4..8 have nothing to do); local lighting with a codec.
  local options
  for options in "${small[*]}" "--order 3 --samples 64 --bounces 0 --quiet" "--order 3 --samples 64 --bounce-threshold 0.05 --quiet" \
                 "--order 2 --samples 64 --bounces 1 --lighting local --compress q16 --passes shadowed,interreflected --quiet"; do
    identical_to_one_machine "$options" 1 3 4
  done
}

case_glossy() {
  # Glossy matrices (every vertex of the room is a glossy sender): two glossy bounces, so
  # bounce 2 reads bounce 1's matrices from the merged pass; the threshold rule ending the
  # series (after bounce 3) before the 4 glossy bounces asked for; local lighting (full
  # packing) with a codec; no glossy bounce; the shadowed matrices alone (no interreflection).
  local options
  for options in "--order 3 --samples 64 --bounces 2 --glossy --glossy-bounces 2 --quiet" \
                 "--order 2 --samples 64 --glossy --glossy-bounces 4 --bounce-threshold 0.05 --quiet" \
                 "--order 2 --samples 64 --bounces 1 --glossy --lighting local --compress q16 --quiet" \
                 "--order 3 --samples 64 --bounces 1 --glossy --glossy-bounces 0 --quiet" \
                 "--order 3 --samples 64 --glossy --glossy-bounces 0 --passes unshadowed,shadowed --quiet"; do
    identical_to_one_machine "$options" 1 2 3
  done
}

# Transfer textures (--texels): the plan picks the atlas once and splits the texel receivers
# too; the texel series runs beside the vertex one in its own files (PLAN.passK.texels.*).
texel_small=(--texels --texture-size 64 --samples 64 --quiet)

case_texels() {
  # Two bounces (the bounce texture of every texel shard made from the whole previous bounce);
  # the visibility vectors of --texel-glossy; the threshold ending both series early; local
  # lighting with a codec and without the unshadowed pass; no interreflection (one pass).
  local options
  for options in "${texel_small[*]} --order 3 --bounces 2" "${texel_small[*]} --order 3 --bounces 2 --texel-glossy" \
                 "${texel_small[*]} --order 2 --bounce-threshold 0.05" \
                 "${texel_small[*]} --order 2 --bounces 1 --lighting local --compress q16 --passes shadowed,interreflected" \
                 "${texel_small[*]} --order 3 --passes unshadowed,shadowed"; do
    identical_to_one_machine "$options" 1 2 3
  done
  # The two series stop apart: at threshold 0.1 the room's vertex series gathers 3 bounces, its
  # texel series 2, so pass 3 has vertex shards and no texel ones (nor a texel merged pass).
  local passes
  run --default -o one.prt "${texel_small[@]}" --order 2 --bounce-threshold 0.1
  passes=$(run plan --default -o room.plan --shards 2 "${texel_small[@]}" --order 2 --bounce-threshold 0.1 --json | plan_passes)
  bake_all room.plan sharded.prt 2 "$passes"
  cmp one.prt sharded.prt || fail "threshold 0.1: the merged texel asset differs from the one-machine bake"
  [[ -e room.plan.pass3.shard1 && -e room.plan.pass3.merged && -e room.plan.pass2.texels.merged && ! -e room.plan.pass3.texels.shard0 &&
     ! -e room.plan.pass3.texels.merged && ! -e room.plan.pass4.merged ]] ||
    fail "threshold 0.1: the vertex series did not go one bounce past the texel series"
  rm -f room.plan*
  # The texel files are there, beside the vertex ones, and named for their series.
  run plan --default -o room.plan --shards 2 "${texel_small[@]}" --order 2 --bounces 1
  bake_all room.plan sharded.prt 2 2
  [[ -s room.plan.pass0.texels.shard1 && -s room.plan.pass1.texels.shard0 && -s room.plan.pass1.texels.merged ]] ||
    fail "a texel plan wrote no texel shards or merged passes"
  # More shards than blocks of 64 texel receivers: refused before any work.
  expect_failure 4 "shard count 30 exceeds the scene's 26 blocks of 64 texel receivers" \
    "$bake" plan --default -o big.plan --shards 30 "${texel_small[@]}"
  [[ ! -e big.plan ]] || fail "a refused plan was written"
}

case_texels_damaged() {
  local options=("${texel_small[@]}" --order 3 --bounces 2)
  run --default -o one.prt "${options[@]}"
  run plan --default -o room.plan --shards 3 "${options[@]}"
  bake_all room.plan merged.prt 3 3
  cmp one.prt merged.prt || fail "the merged texel asset differs from the one-machine bake"
  # A missing texel shard: named by its merge, by merge -o, and by the next bounce's shards.
  mv room.plan.pass1.texels.shard2 saved.shard
  expect_failure 3 "texel shard 2 of pass 1 \('room.plan.pass1.texels.shard2'\) is missing \(run prt-bake bake-shard --plan room.plan --shard 2 --pass 1\)" \
    "$bake" merge --plan room.plan --pass 1
  expect_failure 3 "texel shard 2 of pass 1 .* is missing" "$bake" merge --plan room.plan -o out.prt
  expect_failure 3 "texel shard 2 of pass 1 .* is missing" "$bake" bake-shard --plan room.plan --shard 0 --pass 2
  mv saved.shard room.plan.pass1.texels.shard2
  expect_failure 3 "texel merged pass 1 .* is missing" \
    bash -c "mv room.plan.pass1.texels.merged saved.merged && '$bake' bake-shard --plan room.plan --shard 1 --pass 2"
  mv saved.merged room.plan.pass1.texels.merged
  # A flipped byte in a texel direct shard's hit records: the bounce shard that reads them
  # refuses it by name and writes nothing; merge -o too.
  cp room.plan.pass0.texels.shard1 saved.shard
  flip_byte room.plan.pass0.texels.shard1 $(($(stat -c %s room.plan.pass0.texels.shard1) - 100))
  expect_failure 4 "texel shard 1 of pass 0 \('room.plan.pass0.texels.shard1'\) is corrupt: payload checksum mismatch" \
    bash -c "rm room.plan.pass1.texels.shard1 && '$bake' bake-shard --plan room.plan --shard 1 --pass 1"
  [[ ! -e room.plan.pass1.texels.shard1 ]] || fail "a texel bounce shard was written from damaged hit records"
  expect_failure 4 "texel shard 1 of pass 0 .* is corrupt: payload checksum mismatch" "$bake" merge --plan room.plan -o out.prt
  cp saved.shard room.plan.pass0.texels.shard1
  run bake-shard --plan room.plan --shard 1 --pass 1 --quiet
  # A flipped byte in a texel bounce shard, cut short, not a shard, a vertex shard in its place.
  flip_byte room.plan.pass2.texels.shard0 100
  expect_failure 4 "texel shard 0 of pass 2 \('room.plan.pass2.texels.shard0'\) is corrupt: payload checksum mismatch" \
    "$bake" merge --plan room.plan -o out.prt
  head -c 1000 room.plan.pass1.texels.shard2 > cut && mv cut room.plan.pass1.texels.shard2
  expect_failure 4 "texel shard 2 of pass 1 .* is corrupt: truncated" "$bake" merge --plan room.plan --pass 1
  cp room.plan.pass1.shard2 room.plan.pass1.texels.shard2
  expect_failure 4 "texel shard 2 of pass 1 .* is corrupt: not a texel bake shard" "$bake" merge --plan room.plan --pass 1
  [[ ! -e out.prt ]] || fail "a failed merge wrote its output"
  # A damaged prepared scene's atlas UVs (its last bytes): refused by its checksum, named.
  flip_byte room.plan.scene $(($(stat -c %s room.plan.scene) - 4))
  expect_failure 4 "the prepared scene \('room.plan.scene'\) is corrupt: payload checksum mismatch" \
    "$bake" bake-shard --plan room.plan --shard 0 --pass 0
}

# A 4-shard plan of the small room with every pass done and merged.
baked_plan() {
  run --default -o one.prt "${small[@]}"
  run plan --default -o room.plan --shards 4 "${small[@]}"
  bake_all room.plan merged.prt 4 3
  cmp one.prt merged.prt || fail "the merged asset differs from the one-machine bake"
}

case_missing() {
  baked_plan
  rm room.plan.pass1.shard2
  expect_failure 3 "shard 2 of pass 1 \('room.plan.pass1.shard2'\) is missing" "$bake" merge --plan room.plan --pass 1
  expect_failure 3 "shard 2 of pass 1 .* is missing" "$bake" merge --plan room.plan -o out.prt
  [[ ! -e out.prt ]] || fail "a failed merge wrote its output"
  # Bounce 2's shards read B^1 from pass 1's shards (merged bounce passes do not hold it).
  expect_failure 3 "shard 2 of pass 1 \('room.plan.pass1.shard2'\) is missing" "$bake" bake-shard --plan room.plan --shard 0 --pass 2
  expect_failure 3 "merged pass 1 .* is missing" bash -c "rm room.plan.pass1.merged && '$bake' bake-shard --plan room.plan --shard 0 --pass 2"
}

case_corrupt() {
  baked_plan
  # A flipped byte in the hit records (near the end), then in the transfer before them: a bounce
  # shard verifies the direct shard's checksum from the blocks' checksums it took while reading
  # the records, and refuses it by name before writing anything.
  cp room.plan.pass0.shard1 saved.shard
  flip_byte room.plan.pass0.shard1 $(($(stat -c %s room.plan.pass0.shard1) - 100))
  expect_failure 4 "shard 1 of pass 0 \('room.plan.pass0.shard1'\) is corrupt: payload checksum mismatch" \
    bash -c "rm room.plan.pass1.shard1 && '$bake' bake-shard --plan room.plan --shard 1 --pass 1"
  [[ ! -e room.plan.pass1.shard1 ]] || fail "a bounce shard was written from damaged hit records"
  cp saved.shard room.plan.pass0.shard1
  run bake-shard --plan room.plan --shard 1 --pass 1 --quiet
  flip_byte room.plan.pass0.shard1 1000
  expect_failure 4 "shard 1 of pass 0 \('room.plan.pass0.shard1'\) is corrupt: payload checksum mismatch" \
    "$bake" bake-shard --plan room.plan --shard 1 --pass 2
  cp saved.shard room.plan.pass0.shard1
  # One flipped byte in the hit records of shard 1's direct pass.
  printf '\xff' | dd of=room.plan.pass0.shard1 bs=1 seek=100000 conv=notrunc status=none
  expect_failure 4 "shard 1 of pass 0 \('room.plan.pass0.shard1'\) is corrupt: payload checksum mismatch" \
    "$bake" merge --plan room.plan -o out.prt
  [[ ! -e out.prt ]] || fail "a failed merge wrote its output"
  # A flipped byte in B^1 of shard 3, which bounce 2's shards read: refused by name.
  flip_byte room.plan.pass1.shard3 200
  expect_failure 4 "shard 3 of pass 1 \('room.plan.pass1.shard3'\) is corrupt: payload checksum mismatch" \
    "$bake" bake-shard --plan room.plan --shard 0 --pass 2
  # Cut short.
  head -c 1000 room.plan.pass2.shard3 > cut && mv cut room.plan.pass2.shard3
  expect_failure 4 "shard 3 of pass 2 .* is corrupt: truncated" "$bake" merge --plan room.plan --pass 2
  # Not a shard at all.
  echo "hello" > room.plan.pass2.shard0
  expect_failure 4 "shard 0 of pass 2 .* is corrupt: not a bake shard" "$bake" merge --plan room.plan --pass 2
  # A damaged plan.
  printf '\x00' | dd of=room.plan bs=1 seek=60 conv=notrunc status=none
  expect_failure 4 "'room.plan': payload checksum mismatch" "$bake" merge --plan room.plan -o out.prt
}

case_mismatched() {
  baked_plan
  # The same room and shards with another seed: a different plan, whose shards fit the ranges.
  run plan --default -o other.plan --shards 4 --order 3 --samples 64 --bounces 2 --seed 7 --quiet
  run bake-shard --plan other.plan --shard 2 --pass 0 --quiet
  cp other.plan.pass0.shard2 room.plan.pass0.shard2
  expect_failure 4 "shard 2 of pass 0 .* belongs to another plan" "$bake" merge --plan room.plan -o out.prt
  # A shard renamed into another shard's place: its header says which one it is.
  cp room.plan.pass1.shard0 room.plan.pass1.shard1
  expect_failure 4 "shard 1 of pass 1 .* holds pass 1 shard 0 over \[0, " "$bake" merge --plan room.plan --pass 1
  # Outside the plan.
  expect_failure 4 "pass 3 is outside the plan's passes 0 … 2" "$bake" bake-shard --plan room.plan --shard 0 --pass 3
  expect_failure 4 "shard 4 is outside the plan's shards 0 … 3" "$bake" bake-shard --plan room.plan --shard 4 --pass 0
}

case_changed_scene() {
  local texels
  # The vertex bake, then a texel bake (whose atlas the plan took from the scene's UVs).
  for texels in "" "--texels --texture-size 32"; do
    cp "$models/glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf" box.gltf
    # shellcheck disable=SC2086
    run plan box.gltf -o box.plan --shards 1 "${small[@]}" $texels
    run bake-shard --plan box.plan --shard 0 --pass 0 --quiet
    sed -i 's/"metallicFactor": 0.0/"metallicFactor": 0.0, "baseColorFactor": [0.5, 0.5, 0.5, 1.0]/' box.gltf
    expect_failure 4 "the scene '.*box.gltf' changed since the plan was made" "$bake" bake-shard --plan box.plan --shard 0 --pass 1
    expect_failure 4 "changed since the plan was made" "$bake" merge --plan box.plan --pass 0
    rm box.gltf
    expect_failure 3 "box.gltf" "$bake" bake-shard --plan box.plan --shard 0 --pass 0
    rm -f box.plan*
  done
}

case_prepared_scene() {
  # A glTF with an external buffer and image: plan stores the prepared scene (room.plan.scene)
  # and each scene file's size and CRC-32C; shards and merges read the former and check the latter.
  cp "$models/glTF2/BoxTextured-glTF/"* .
  run BoxTextured.gltf -o one.prt "${small[@]}"
  run plan BoxTextured.gltf -o box.plan --shards 1 "${small[@]}"
  [[ -s box.plan.scene ]] || fail "plan wrote no prepared scene"
  touch BoxTextured0.bin  # a new time, the same bytes: still the planned scene
  bake_all box.plan sharded.prt 1 3
  cmp one.prt sharded.prt || fail "the box merged from its prepared scene differs from the one-machine bake (name included)"
  # A changed byte in the external buffer (same size), then a missing image: refused, named.
  cp BoxTextured0.bin saved.bin
  flip_byte BoxTextured0.bin 100
  expect_failure 4 "the scene '.*BoxTextured.gltf' changed since the plan was made \(its file '.*BoxTextured0.bin' is" \
    "$bake" bake-shard --plan box.plan --shard 0 --pass 0
  mv saved.bin BoxTextured0.bin
  mv CesiumLogoFlat.png saved.png
  expect_failure 3 "CesiumLogoFlat.png" "$bake" merge --plan box.plan --pass 0
  mv saved.png CesiumLogoFlat.png
  run merge --plan box.plan --pass 0 --quiet
  # The prepared scene missing, damaged, or another plan's.
  mv box.plan.scene saved.scene
  expect_failure 3 "the prepared scene \('box.plan.scene'\) is missing" "$bake" bake-shard --plan box.plan --shard 0 --pass 1
  cp saved.scene box.plan.scene
  flip_byte box.plan.scene 200
  expect_failure 4 "the prepared scene .* is corrupt: payload checksum mismatch" "$bake" merge --plan box.plan -o out.prt
  run plan BoxTextured.gltf -o other.plan --shards 1 --order 3 --samples 64 --bounces 2 --seed 7 --quiet
  cp other.plan.scene box.plan.scene
  expect_failure 4 "the prepared scene .* belongs to another plan" "$bake" bake-shard --plan box.plan --shard 0 --pass 1
  [[ ! -e out.prt ]] || fail "a failed merge wrote its output"
}

case_usage() {
  expect_failure 2 "missing --shards" "$bake" plan --default -o p.plan
  expect_failure 2 "--shards '0' is out of range" "$bake" plan --default -o p.plan --shards 0
  expect_failure 4 "shard count 400 exceeds the scene's 320 blocks of 64 vertices" "$bake" plan --default -o p.plan --shards 400
  # Normal maps shade texels, and the prepared scene does not hold them (yet).
  expect_failure 4 "sharded bakes do not support --texels on a normal-mapped scene yet" \
    "$bake" plan "$models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf" -o p.plan --shards 1 --texels --texture-size 64
  expect_failure 2 "unknown option '--bogus'" "$bake" plan --default -o p.plan --shards 2 --bogus
  [[ ! -e p.plan ]] || fail "a refused plan was written"
  expect_failure 3 "no-such.plan" "$bake" bake-shard --plan no-such.plan --shard 0 --pass 0
  expect_failure 2 "missing --pass" "$bake" bake-shard --plan no-such.plan --shard 0
  expect_failure 2 "give --pass K .* or -o ASSET" "$bake" merge --plan no-such.plan
  expect_failure 4 "not a bake plan" bash -c "echo nope > fake.plan && '$bake' merge --plan fake.plan --pass 0"
}

"case_$case_name"
echo "PASS: $case_name"
