// The sharded bake's files on untrusted bytes (docs/scale-out.md, "Files"): a valid file
// round-trips; every shorter prefix, every single flipped byte and every appended byte is
// refused with an error, never a crash or a silent success.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "baker/shard/bake_plan.h"
#include "baker/shard/prepared_scene.h"
#include "baker/shard/shard_container.h"
#include "baker/shard/shard_payloads.h"
#include "baker/transfer/transfer_range.h"
#include "prt/checksum.h"

namespace prt::bake {
namespace {

// texels: a texel plan, two atlases over the 300 triangles and 300 receivers in 3 ranges.
BakePlan samplePlan(bool texels = false) {
  BakePlan p;
  p.scenePath = "/data/scene.glb";
  p.workingDirectory = "/data";
  p.bakeArgs = {"/data/scene.glb", "-o", "x.plan", "--order", "3"};
  p.sceneHash = 0x12345678u;
  p.sceneName = "scene";
  p.sceneFiles = {{"/data/scene.gltf", 1234, 0xabcdef01u}, {"/data/scene.bin", 99, 7}};
  p.vertices = 200;
  p.triangles = 300;
  p.order = 3;
  p.passes = 3;
  EXPECT_TRUE(planRanges(p.vertices, 3, &p.shards).isOk());
  if (texels) {
    p.atlases = {{64, 64, 0, 200}, {32, 16, 200, 100}};
    p.texelReceivers = 300;
    EXPECT_TRUE(planRanges(p.texelReceivers, 3, &p.texelShards, "texel receivers").isOk());
  }
  return p;
}

TEST(ShardFormat, PlanRangesTileTheVerticesInWholeBlocks) {
  std::vector<VertexRange> r;
  ASSERT_TRUE(planRanges(20434, 4, &r).isOk());
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0].begin, 0u);
  for (std::size_t i = 0; i + 1 < r.size(); ++i) {
    EXPECT_EQ(r[i].end, r[i + 1].begin);
    EXPECT_EQ(r[i].end % kBlockVertices, 0u);
  }
  EXPECT_EQ(r.back().end, 20434u);
  EXPECT_FALSE(planRanges(20434, 0, &r).isOk());
  EXPECT_FALSE(planRanges(100, 3, &r).isOk());  // 2 blocks
  EXPECT_TRUE(planRanges(100, 2, &r).isOk());
}

TEST(ShardFormat, PlanRoundTripsAndRefusesDamage) {
  for (bool texels : {false, true}) {
    BakePlan p = samplePlan(texels);
    const std::vector<std::uint8_t> bytes = encodeBakePlan(&p);
    BakePlan q;
    ASSERT_TRUE(decodeBakePlan(bytes, &q).isOk());
    EXPECT_EQ(q.scenePath, p.scenePath);
    EXPECT_EQ(q.bakeArgs, p.bakeArgs);
    EXPECT_EQ(q.sceneHash, p.sceneHash);
    EXPECT_EQ(q.sceneName, "scene");
    ASSERT_EQ(q.sceneFiles.size(), 2u);
    EXPECT_EQ(q.sceneFiles[1].path, "/data/scene.bin");
    EXPECT_EQ(q.sceneFiles[0].bytes, 1234u);
    EXPECT_EQ(q.sceneFiles[0].crc32c, 0xabcdef01u);
    EXPECT_EQ(q.shards.size(), 3u);
    EXPECT_EQ(q.id, p.id);
    ASSERT_EQ(q.atlases.size(), texels ? 2u : 0u);
    EXPECT_EQ(q.texelReceivers, texels ? 300u : 0u);
    ASSERT_EQ(q.texelShards.size(), texels ? 3u : 0u);
    if (texels) {
      EXPECT_EQ(q.atlases[1].height, 16u);
      EXPECT_EQ(q.atlases[1].firstTriangle, 200u);
      EXPECT_EQ(q.texelShards[1].begin, p.texelShards[1].begin);
      EXPECT_EQ(q.texelShards[2].end, 300u);
    }
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      EXPECT_FALSE(decodeBakePlan(std::span(bytes).first(n), &q).isOk()) << "prefix of " << n << " bytes";
    }
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      std::vector<std::uint8_t> b = bytes;
      b[i] ^= 0x01;
      EXPECT_FALSE(decodeBakePlan(b, &q).isOk()) << "byte " << i << " flipped";
    }
    std::vector<std::uint8_t> longer = bytes;
    longer.push_back(0);
    const Status s = decodeBakePlan(longer, &q);
    EXPECT_EQ(s.code(), StatusCode::kCorrupt) << s.message();
  }
  // Atlases that leave triangles uncovered, and texel ranges past the receivers: refused, named.
  BakePlan gap = samplePlan(true);
  gap.atlases[1].triangleCount = 99;
  BakePlan q;
  Status s = decodeBakePlan(encodeBakePlan(&gap), &q);
  EXPECT_EQ(s.code(), StatusCode::kCorrupt);
  EXPECT_NE(s.message().find("the atlases cover 299 of 300 triangles"), std::string::npos) << s.message();
  BakePlan past = samplePlan(true);
  past.texelReceivers = 200;
  s = decodeBakePlan(encodeBakePlan(&past), &q);
  EXPECT_EQ(s.code(), StatusCode::kCorrupt);
  EXPECT_NE(s.message().find("texel shard 2 covers"), std::string::npos) << s.message();
}

// Two triangles over four vertices, with specular materials when `glossy`.
Scene sampleScene(bool glossy) {
  Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5f}};
  s.normals.assign(4, Vec3{0, 0, 1});
  s.albedo = {{0.1f, 0.2f, 0.3f}, {0.4f, 0.5f, 0.6f}, {0.7f, 0.8f, 0.9f}, {1, 1, 1}};
  s.indices = {0, 1, 2, 2, 1, 3};
  if (glossy) s.specular = {{{0.04f, 0.04f, 0.04f}, 10.0f, 1.0f}, {}, {{0.9f, 0.6f, 0.3f}, 200.0f, 0.5f}, {}};
  return s;
}

TEST(ShardFormat, PreparedSceneRoundTripsItsHashAndRefusesDamage) {
  for (bool glossy : {false, true}) {
    for (bool texels : {false, true}) {
      const Scene s = sampleScene(glossy);
      const std::vector<Uv> uv = texels ? std::vector<Uv>{{0.1f, 0.2f}, {0.3f, 0.4f}, {0.5f, 0.6f}, {0.7f, 0.875f}} : std::vector<Uv>{};
      const std::vector<std::uint8_t> payload = encodePreparedScene(s, uv);
      // The payload's checksum is the scene hash: the container's check is the plan's.
      EXPECT_EQ(crc32c(payload), sceneHash(s, uv));
      if (texels) {
        EXPECT_NE(sceneHash(s, uv), sceneHash(s));  // another atlas is another plan's scene
      }
      Scene t;
      std::vector<Uv> tuv{{9, 9}};
      ASSERT_TRUE(decodePreparedScene(payload, &t, &tuv).isOk());
      ASSERT_EQ(tuv.size(), uv.size());
      if (texels) {
        EXPECT_EQ(tuv[3].v, 0.875f);
      }
      EXPECT_EQ(t.indices, s.indices);
      EXPECT_EQ(sceneHash(t, tuv), sceneHash(s, uv));
      EXPECT_EQ(t.specular.size(), glossy ? 4u : 0u);
      if (glossy) {
        EXPECT_EQ(t.specular[2].exponent, 200.0f);
        EXPECT_EQ(t.specular[2].f90, 0.5f);
      }
      for (std::size_t n = 0; n < payload.size(); ++n) {
        // Every prefix is cut short: the flags say which arrays follow.
        Scene u;
        EXPECT_FALSE(decodePreparedScene(std::span(payload).first(n), &u).isOk()) << "prefix of " << n << " bytes";
      }
      std::vector<std::uint8_t> longer = payload;
      longer.push_back(0);
      EXPECT_EQ(decodePreparedScene(longer, &t).code(), StatusCode::kCorrupt);
    }
  }
  // An index outside the vertices would read past them in every gather: refused.
  Scene bad = sampleScene(false);
  bad.indices[4] = 4;
  Scene t;
  const Status st = decodePreparedScene(encodePreparedScene(bad), &t);
  EXPECT_EQ(st.code(), StatusCode::kCorrupt);
  EXPECT_NE(st.message().find("index 4 is not below the 4 vertices"), std::string::npos) << st.message();
  // In its container, any flipped byte is caught.
  ShardHeader h;
  h.kind = ShardFileKind::kPreparedScene;
  h.planId = 3;
  h.vertexEnd = 4;
  const std::vector<std::uint8_t> file = encodeShardFile(h, encodePreparedScene(sampleScene(true)));
  ShardHeader g;
  std::span<const std::uint8_t> view;
  ASSERT_TRUE(decodeShardFile(file, ShardFileKind::kPreparedScene, &g, &view).isOk());
  EXPECT_EQ(g.payloadCrc, sceneHash(sampleScene(true)));
  EXPECT_EQ(decodeShardFile(file, ShardFileKind::kShard, &g, &view).code(), StatusCode::kBadMagic);
  for (std::size_t i = 0; i < file.size(); ++i) {
    std::vector<std::uint8_t> b = file;
    b[i] ^= 0x10;
    EXPECT_FALSE(decodeShardFile(b, ShardFileKind::kPreparedScene, &g, &view).isOk()) << "byte " << i << " flipped";
  }
}

TEST(ShardFormat, ShardFileOfAnotherKindIsNotRead) {
  BakePlan p = samplePlan();
  const std::vector<std::uint8_t> plan = encodeBakePlan(&p);
  ShardHeader h;
  std::span<const std::uint8_t> payload;
  const Status s = decodeShardFile(plan, ShardFileKind::kShard, &h, &payload);
  EXPECT_EQ(s.code(), StatusCode::kBadMagic);
  EXPECT_NE(s.message().find("not a bake shard"), std::string::npos) << s.message();
  // A texel series' file never passes for the vertex series' (their ranges count other things).
  ShardHeader t;
  t.kind = ShardFileKind::kTexelShard;
  const std::vector<std::uint8_t> texel = encodeShardFile(t, std::vector<std::uint8_t>(8, 0));
  EXPECT_EQ(decodeShardFile(texel, ShardFileKind::kShard, &h, &payload).code(), StatusCode::kBadMagic);
  EXPECT_TRUE(decodeShardFile(texel, ShardFileKind::kTexelShard, &h, &payload).isOk());
  t.kind = ShardFileKind::kTexelMergedPass;
  const Status m = decodeShardFile(encodeShardFile(t, {}), ShardFileKind::kMergedPass, &h, &payload);
  EXPECT_EQ(m.code(), StatusCode::kBadMagic);
}

// A direct shard of 70 vertices (two blocks) with hits, at order 2.
DirectShard sampleDirect() {
  DirectShard d;
  d.unshadowed.assign(70 * 4, 0.25f);
  d.shadowed.assign(70 * 4, 0.125f);
  d.hasHits = true;
  d.blocks.resize(2);
  d.blocks[0].hitStart.assign(65, 0);
  d.blocks[0].hitStart[64] = 2;
  for (int v = 1; v < 64; ++v) d.blocks[0].hitStart[v] = 1;
  d.blocks[0].hits = {{5, 100, 200, 0.5f}, {7, 0, 65535, 0.25f}};
  d.blocks[1].hitStart.assign(7, 0);
  d.blocks[1].hitStart[6] = 1;
  d.blocks[1].hits = {{9, 1, 2, 0.125f}};
  return d;
}

TEST(ShardFormat, DirectShardRoundTripsAndRefusesDamage) {
  const DirectShard d = sampleDirect();
  const std::vector<std::uint8_t> payload = encodeDirectShard(d);
  DirectShard e;
  ASSERT_TRUE(decodeDirectShard(payload, 70, 4, 0, DirectShardPart::kHits, &e).isOk());
  EXPECT_TRUE(e.unshadowed.empty() && e.shadowed.empty());  // the bounce shards' reading copies no transfer
  ASSERT_EQ(e.hitViews.size(), 2u);
  EXPECT_EQ(std::vector<std::uint32_t>(e.hitViews[0].hitStart.begin(), e.hitViews[0].hitStart.end()), d.blocks[0].hitStart);
  EXPECT_EQ(std::vector<std::uint32_t>(e.hitViews[1].hitStart.begin(), e.hitViews[1].hitStart.end()), d.blocks[1].hitStart);
  ASSERT_EQ(e.hitViews[1].hits.size(), 1u);
  EXPECT_EQ(e.hitViews[1].hits[0].triangle, 9u);
  EXPECT_EQ(e.hitViews[0].hits[1].v, 65535);
  // Views into the payload, not copies.
  EXPECT_GE(reinterpret_cast<const std::uint8_t*>(e.hitViews[0].hits.data()), payload.data());
  EXPECT_LT(reinterpret_cast<const std::uint8_t*>(e.hitViews[0].hits.data()), payload.data() + payload.size());
  // A misaligned payload (a copy one byte in) is refused, not read misaligned.
  std::vector<std::uint8_t> shifted(payload.size() + 1);
  std::copy(payload.begin(), payload.end(), shifted.begin() + 1);
  EXPECT_EQ(decodeDirectShard(std::span(shifted).subspan(1), 70, 4, 0, DirectShardPart::kHits, &e).code(), StatusCode::kCorrupt);
  // Another vertex count or order.
  EXPECT_FALSE(decodeDirectShard(payload, 69, 4, 0, DirectShardPart::kHits, &e).isOk());
  EXPECT_FALSE(decodeDirectShard(payload, 70, 9, 0, DirectShardPart::kHits, &e).isOk());
  for (std::size_t n = 0; n < payload.size(); ++n) {
    EXPECT_FALSE(decodeDirectShard(std::span(payload).first(n), 70, 4, 0, DirectShardPart::kHits, &e).isOk()) << "prefix of " << n << " bytes";
  }
  // Without the hits (the merges): the transfer alone, the hit records' sizes still checked.
  DirectShard f;
  ASSERT_TRUE(decodeDirectShard(payload, 70, 4, 0, DirectShardPart::kTransfer, &f).isOk());
  EXPECT_EQ(f.unshadowed, d.unshadowed);
  EXPECT_EQ(f.shadowed, d.shadowed);
  EXPECT_TRUE(f.hasHits);
  EXPECT_TRUE(f.hitViews.empty());
  EXPECT_FALSE(decodeDirectShard(std::span(payload).first(payload.size() - 1), 70, 4, 0, DirectShardPart::kTransfer, &f).isOk());
  // In a file, any flipped byte is caught by a checksum.
  ShardHeader h;
  h.planId = 7;
  h.pass = 0;
  h.shard = 1;
  h.vertexBegin = 64;
  h.vertexEnd = 134;
  const std::vector<std::uint8_t> file = encodeShardFile(h, payload);
  ShardHeader g;
  std::span<const std::uint8_t> view;
  ASSERT_TRUE(decodeShardFile(file, ShardFileKind::kShard, &g, &view).isOk());
  EXPECT_EQ(g.vertexBegin, 64u);
  for (std::size_t i = 0; i < file.size(); i += 7) {
    std::vector<std::uint8_t> b = file;
    b[i] ^= 0x80;
    EXPECT_FALSE(decodeShardFile(b, ShardFileKind::kShard, &g, &view).isOk()) << "byte " << i << " flipped";
  }
}

// A texel direct shard with visibility vectors (--texel-glossy): round-trips; refused where the
// plan has none, with another vector size, or together with the glossy flag.
TEST(ShardFormat, DirectShardVisibilityRoundTripsAndRefusesDamage) {
  DirectShard d = sampleDirect();
  d.hasVisibility = true;
  d.visibility.assign(70 * 9, 0.5f);
  d.visibility[9 * 69 + 8] = -2.0f;
  const std::vector<std::uint8_t> payload = encodeDirectShard(d);
  DirectShard e;
  ASSERT_TRUE(decodeDirectShard(payload, 70, 4, 0, DirectShardPart::kTransfer, &e, 9).isOk());
  EXPECT_TRUE(e.hasVisibility);
  EXPECT_EQ(e.visibility, d.visibility);
  EXPECT_EQ(e.shadowed, d.shadowed);
  ASSERT_TRUE(decodeDirectShard(payload, 70, 4, 0, DirectShardPart::kHits, &e, 9).isOk());
  ASSERT_EQ(e.hitViews.size(), 2u);
  EXPECT_EQ(e.hitViews[1].hits[0].triangle, 9u);
  Status s = decodeDirectShard(payload, 70, 4, 0, DirectShardPart::kTransfer, &e, 0);
  EXPECT_EQ(s.code(), StatusCode::kCorrupt);
  EXPECT_NE(s.message().find("visibility vectors the plan has none of"), std::string::npos) << s.message();
  EXPECT_FALSE(decodeDirectShard(payload, 70, 4, 0, DirectShardPart::kTransfer, &e, 16).isOk());
  for (std::size_t n = 0; n < payload.size(); ++n) {
    EXPECT_FALSE(decodeDirectShard(std::span(payload).first(n), 70, 4, 0, DirectShardPart::kTransfer, &e, 9).isOk())
        << "prefix of " << n << " bytes";
  }
  std::vector<std::uint8_t> both = payload;
  both[0] |= 2;  // glossy too: never in one file
  EXPECT_EQ(decodeDirectShard(both, 70, 4, 4, DirectShardPart::kTransfer, &e, 9).code(), StatusCode::kCorrupt);
}

// The records' values are checked once, by their reader (gatherBounceRange), since the
// decoder views them unchecked: a triangle outside the scene (an index: it would read past
// B^{b-1}), a weight that is not finite, a glossy hit's sample index past the samples.
TEST(ShardFormat, HitRecordsAreCheckedByTheirReader) {
  const Scene scene = sampleScene(false);  // 4 vertices, 2 triangles: one block
  BakeOptions o;
  o.order = 2;
  o.samples = 64;
  o.threads = 1;
  const std::vector<float> previous(4 * 3 * 4, 1.0f);
  const std::vector<std::uint32_t> hitStart = {0, 1, 1, 1, 1};
  const std::vector<std::uint32_t> pastSamples = {64}, aSample = {0};
  auto gather = [&](Hit hit, const std::vector<std::uint32_t>* samples) {
    const std::vector<Hit> hits = {hit};
    HitBlockView view{hitStart, hits, samples ? std::span<const std::uint32_t>(*samples) : std::span<const std::uint32_t>()};
    std::vector<float> current, matrices;
    std::vector<double> energy;
    PassStats stats;
    const GlossyRangeBounce glossy{{}, &matrices};
    std::vector<std::uint32_t> crc;
    const Status s = gatherBounceRange(scene, o, 1, 0, std::span(&view, 1), previous, samples ? &glossy : nullptr, &current,
                                       &energy, &crc, &stats);
    // Each block's records' checksum, taken as they were read (the caller's deferred check).
    if (s.isOk()) {
      EXPECT_EQ(crc, std::vector<std::uint32_t>{crc32c({reinterpret_cast<const std::uint8_t*>(hits.data()), 12})});
    }
    return s;
  };
  EXPECT_TRUE(gather({1, 100, 200, 0.5f}, nullptr).isOk());
  EXPECT_EQ(gather({2, 100, 200, 0.5f}, nullptr).code(), StatusCode::kCorrupt);  // triangle 2 of 2
  EXPECT_EQ(gather({1, 100, 200, std::numeric_limits<float>::quiet_NaN()}, nullptr).code(), StatusCode::kCorrupt);
  EXPECT_EQ(gather({1, 100, 200, std::numeric_limits<float>::infinity()}, nullptr).code(), StatusCode::kCorrupt);
  EXPECT_EQ(gather({1, 100, 200, 0.5f}, &pastSamples).code(), StatusCode::kCorrupt);  // sample 64 of 64
  // A glossy bounce checks the records before its glossy gather reads them (which would
  // otherwise refuse these empty senders' matrices with kInvalidArgument).
  EXPECT_EQ(gather({2, 100, 200, 0.5f}, &aSample).code(), StatusCode::kCorrupt);
  EXPECT_EQ(gather({1, 100, 200, std::numeric_limits<float>::quiet_NaN()}, &aSample).code(), StatusCode::kCorrupt);
  EXPECT_EQ(gather({1, 100, 200, 0.5f}, &aSample).code(), StatusCode::kInvalidArgument);
}

TEST(ShardFormat, BounceShardAndMergedPassRoundTrip) {
  BounceShard b;
  b.bounce.assign(70 * 12, 0.5f);
  b.blockEnergy = {1.0, 2.0};
  const std::vector<std::uint8_t> bp = encodeBounceShard(b);
  BounceShardView c;
  ASSERT_TRUE(decodeBounceShard(bp, 70, 4, false, &c).isOk());
  EXPECT_EQ(c.blockEnergy, b.blockEnergy);
  EXPECT_EQ(std::vector<float>(c.bounce.begin(), c.bounce.end()), b.bounce);
  EXPECT_EQ(reinterpret_cast<const std::uint8_t*>(c.bounce.data()), bp.data());  // viewed in place
  EXPECT_FALSE(decodeBounceShard(bp, 64, 4, false, &c).isOk());
  EXPECT_FALSE(decodeBounceShard(std::span(bp).first(bp.size() - 1), 70, 4, false, &c).isOk());
  EXPECT_FALSE(decodeBounceShard(bp, 70, 4, true, &c).isOk());  // a glossy bounce's matrices are missing

  // A merged bounce pass: the energies and the stop mark, no B^b (its shards hold it).
  MergedPass m;
  m.final = true;
  m.energies = {3.0, 1.0};
  const std::vector<std::uint8_t> mp = encodeMergedPass(m);
  EXPECT_EQ(mp.size(), 8u + 2 * 8 + 8 + 8);
  MergedPassView n;
  ASSERT_TRUE(decodeMergedPass(mp, 1, 0, 0, &n).isOk());
  EXPECT_TRUE(n.final);
  EXPECT_EQ(n.energies, m.energies);
  EXPECT_TRUE(n.bounce.empty());
  EXPECT_FALSE(decodeMergedPass(mp, 2, 0, 0, &n).isOk());    // energies of another pass
  EXPECT_FALSE(decodeMergedPass(mp, 1, 840, 0, &n).isOk());  // a B^0 expected
  EXPECT_FALSE(decodeMergedPass(mp, 1, 0, 48, &n).isOk());   // glossy senders' matrices expected
  for (std::size_t len = 0; len < mp.size(); ++len) {
    EXPECT_FALSE(decodeMergedPass(std::span(mp).first(len), 1, 0, 0, &n).isOk()) << "prefix of " << len << " bytes";
  }
  // Merged pass 0: B^0 of every vertex, viewed in place.
  MergedPass z;
  z.energies = {3.0};
  const std::vector<float> bounce0(70 * 12, 0.25f);
  z.bounce = bounce0;
  const std::vector<std::uint8_t> zp = encodeMergedPass(z);
  ASSERT_TRUE(decodeMergedPass(zp, 0, 70 * 12, 0, &n).isOk());
  EXPECT_FALSE(n.final);
  EXPECT_EQ(std::vector<float>(n.bounce.begin(), n.bounce.end()), bounce0);
  EXPECT_GE(reinterpret_cast<const std::uint8_t*>(n.bounce.data()), zp.data());
  EXPECT_LT(reinterpret_cast<const std::uint8_t*>(n.bounce.data()), zp.data() + zp.size());
  EXPECT_FALSE(decodeMergedPass(zp, 0, 71 * 12, 0, &n).isOk());
  EXPECT_FALSE(decodeMergedPass(zp, 0, 0, 0, &n).isOk());  // a B^0 where none belongs
  for (std::size_t len = 0; len < zp.size(); len += 97) {
    EXPECT_FALSE(decodeMergedPass(std::span(zp).first(len), 0, 70 * 12, 0, &n).isOk()) << "prefix of " << len << " bytes";
  }
}

// The glossy payloads (--glossy): a direct shard with shadowed matrices and each hit's sample
// index, a glossy bounce's M^b, a merged pass with the senders' matrices. Every prefix,
// every appended byte, and every wrong size the plan implies is refused.
TEST(ShardFormat, GlossyPayloadsRoundTripAndRefuseDamage) {
  DirectShard d = sampleDirect();
  d.glossy = true;
  d.glossyShadowed.assign(70 * 10, 0.5f);  // order 2, symmetric packing: 10 entries
  d.blocks[0].hitSample = {3, 63};
  d.blocks[1].hitSample = {0};
  const std::vector<std::uint8_t> payload = encodeDirectShard(d);
  DirectShard e;
  ASSERT_TRUE(decodeDirectShard(payload, 70, 4, 10, DirectShardPart::kHits, &e).isOk());
  EXPECT_TRUE(e.glossy);
  EXPECT_TRUE(e.glossyShadowed.empty());
  DirectShard f;
  ASSERT_TRUE(decodeDirectShard(payload, 70, 4, 10, DirectShardPart::kTransfer, &f).isOk());
  EXPECT_EQ(f.glossyShadowed, d.glossyShadowed);
  EXPECT_EQ(std::vector<std::uint32_t>(e.hitViews[0].hitSample.begin(), e.hitViews[0].hitSample.end()), d.blocks[0].hitSample);
  EXPECT_EQ(std::vector<std::uint32_t>(e.hitViews[1].hitSample.begin(), e.hitViews[1].hitSample.end()), d.blocks[1].hitSample);
  EXPECT_FALSE(decodeDirectShard(payload, 70, 4, 16, DirectShardPart::kHits, &e).isOk());  // another packing
  for (std::size_t n = 0; n < payload.size(); ++n) {
    EXPECT_FALSE(decodeDirectShard(std::span(payload).first(n), 70, 4, 10, DirectShardPart::kHits, &e).isOk()) << "prefix of " << n << " bytes";
  }
  std::vector<std::uint8_t> longer = payload;
  longer.push_back(0);
  EXPECT_FALSE(decodeDirectShard(longer, 70, 4, 10, DirectShardPart::kHits, &e).isOk());
  std::vector<std::uint8_t> flags = payload;
  flags[0] |= 4;  // a flag this format does not have
  EXPECT_EQ(decodeDirectShard(flags, 70, 4, 10, DirectShardPart::kHits, &e).code(), StatusCode::kCorrupt);

  BounceShard b;
  b.bounce.assign(70 * 12, 0.5f);
  b.blockEnergy = {1.0, 2.0};
  b.matrices.assign(70 * 3 * 16, 0.125f);
  const std::vector<std::uint8_t> bp = encodeBounceShard(b);
  BounceShardView c;
  ASSERT_TRUE(decodeBounceShard(bp, 70, 4, true, &c).isOk());
  EXPECT_EQ(std::vector<float>(c.matrices.begin(), c.matrices.end()), b.matrices);
  EXPECT_FALSE(decodeBounceShard(bp, 70, 4, false, &c).isOk());  // matrices where none belong
  for (std::size_t n = 0; n < bp.size(); n += 13) {
    EXPECT_FALSE(decodeBounceShard(std::span(bp).first(n), 70, 4, true, &c).isOk()) << "prefix of " << n << " bytes";
  }

  MergedPass m;
  m.energies = {3.0};
  const std::vector<float> bounce(70 * 12, 0.25f);
  m.bounce = bounce;
  m.senderMatrices.assign(5 * 10, 2.0f);
  const std::vector<std::uint8_t> mp = encodeMergedPass(m);
  MergedPassView n;
  ASSERT_TRUE(decodeMergedPass(mp, 0, 70 * 12, 50, &n).isOk());
  EXPECT_EQ(std::vector<float>(n.senderMatrices.begin(), n.senderMatrices.end()), m.senderMatrices);
  EXPECT_EQ(decodeMergedPass(mp, 0, 70 * 12, 0, &n).code(), StatusCode::kCorrupt);
  EXPECT_EQ(decodeMergedPass(mp, 0, 70 * 12, 60, &n).code(), StatusCode::kCorrupt);
  for (std::size_t len = 0; len < mp.size(); len += 29) {
    EXPECT_FALSE(decodeMergedPass(std::span(mp).first(len), 0, 70 * 12, 50, &n).isOk()) << "prefix of " << len << " bytes";
  }
  std::vector<std::uint8_t> padded = mp;
  padded.push_back(0);
  EXPECT_FALSE(decodeMergedPass(padded, 0, 70 * 12, 50, &n).isOk());
}

}  // namespace
}  // namespace prt::bake
