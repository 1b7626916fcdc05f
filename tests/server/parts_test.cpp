// Assets served as parts (/parts/<hash>) by a real prt-serve: the catalogue's part lists
// tile each file, every part URL serves its bytes in every coding with immutable caching
// and validators, encoded transfers are cut at band boundaries, shared parts have one URL,
// the size limit leaves large assets whole, and bad part URLs are 400/404.
#include <gtest/gtest.h>

#include <cctype>
#include <map>
#include <set>
#include <thread>
#include <tuple>

#include "encoded_asset.h"
#include "prt/transfer_codec.h"
#include "serve_env.h"

namespace prt::serve::test {
namespace {

constexpr const char* kImmutable = "public, max-age=31536000, immutable";

std::string asString(const std::vector<std::uint8_t>& v) { return std::string(v.begin(), v.end()); }

// A tree with the usual assets plus an asset holding encoded transfers (encoded.prt), one
// with transfer textures (texel.prt), the same with a TPFL visibility pass (visibility.prt), a
// twin of room.prt that differs only in its name (twin.prt), and a server on it.
struct PartsServer {
  TestTree tree;
  EncodedTransferAsset encoded;
  TexelTransferAsset texel, visibility;
  std::vector<std::uint8_t> twin;
  std::unique_ptr<ServerProcess> server;
  int port = 0;
};

PartsServer& partsServer() {
  static PartsServer shared = [] {
    PartsServer s;
    s.tree = makeTestTree(workDir());
    s.encoded = makeEncodedTransferAsset(3000, 4, 7);
    writeFile(s.tree.root + "/encoded.prt", s.encoded.bytes);
    s.texel = makeTexelTransferAsset(400, 3, 9);
    writeFile(s.tree.root + "/texel.prt", s.texel.bytes);
    s.visibility = makeTexelTransferAsset(400, 3, 11, true);
    writeFile(s.tree.root + "/visibility.prt", s.visibility.bytes);
    s.twin = makeAssetBytes(6000, 4, 1, "twin of the room");
    writeFile(s.tree.root + "/twin.prt", s.twin);
    s.server = startServer(s.tree, {"--threads", "2"}, "parts.log");
    s.port = s.server ? s.server->port() : 0;
    return s;
  }();
  if (!shared.server) ADD_FAILURE() << "the parts server is not running";
  return shared;
}

Json catalogue(int port) {
  const HttpResponse r = fetch(port, "/api/scenes");
  Json j;
  std::string error;
  EXPECT_EQ(r.status, 200);
  EXPECT_TRUE(parseJson(r.body, &j, &error)) << error;
  return j;
}

const Json* entry(const Json& cat, const std::string& file) {
  for (const Json& e : asArray(cat.at("scenes"))) {
    if (e.at("file").get<std::string>() == file) return &e;
  }
  return nullptr;
}

std::string decodeAs(const std::string& encoding, const std::string& body) {
  if (encoding.empty()) return body;
  if (encoding == "gzip") return gunzip(body);
  if (encoding == "zstd") return unzstd(body);
  if (encoding == "br") return unbrotli(body);
  return "<unknown encoding " + encoding + ">";
}

// Fetches every part of `e` (identity) and places it at its offset in a buffer of the
// asset's size, as a progressive client does; checks the list tiles the file on the way.
std::string assemble(int port, const Json& e) {
  const Json& parts = e.at("parts");
  EXPECT_TRUE(parts.is_array()) << e.at("file").get<std::string>();
  std::string file(static_cast<std::size_t>(e.at("bytes").get<double>()), '\0');
  std::uint64_t at = 0;
  for (const Json& p : asArray(parts)) {
    const auto offset = static_cast<std::uint64_t>(p.at("offset").get<double>());
    const auto size = static_cast<std::uint64_t>(p.at("size").get<double>());
    EXPECT_EQ(offset, at) << p.at("url").get<std::string>();
    EXPECT_GT(size, 0u);
    at = offset + size;
    const HttpResponse r = fetch(port, p.at("url").get<std::string>());
    EXPECT_EQ(r.status, 200) << p.at("url").get<std::string>();
    EXPECT_EQ(r.body.size(), size) << p.at("url").get<std::string>();
    if (r.body.size() == size && offset + size <= file.size()) file.replace(offset, size, r.body);
  }
  EXPECT_EQ(at, file.size()) << e.at("file").get<std::string>();
  return file;
}

TEST(Parts, CatalogueListsPartsThatTileEveryAsset) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  struct Expect {
    const char* file;
    const std::vector<std::uint8_t>* bytes;
  };
  for (const Expect& x : {Expect{"room.prt", &s.tree.room}, Expect{"sub/small.prt", &s.tree.small},
                          Expect{"encoded.prt", &s.encoded.bytes}, Expect{"texel.prt", &s.texel.bytes},
                          Expect{"twin.prt", &s.twin}}) {
    SCOPED_TRACE(x.file);
    const Json* e = entry(cat, x.file);
    ASSERT_NE(e, nullptr);
    ASSERT_TRUE(e->contains("parts"));
    const Json& parts = e->at("parts");
    ASSERT_GE(asArray(parts).size(), 2u);
    EXPECT_EQ(parts.at(0).at("kind").get<std::string>(), "head");
    EXPECT_FALSE(parts.at(0).contains("section"));
    AssetSummary summary;
    ASSERT_TRUE(verifyAsset(*x.bytes, &summary).isOk());
    // The head ends where the first payload begins; every section of the table is listed.
    std::uint64_t firstPayload = x.bytes->size();
    for (const AssetSectionInfo& sec : summary.sections) firstPayload = std::min(firstPayload, sec.offset);
    EXPECT_EQ(parts.at(0).at("size").get<double>(), static_cast<double>(firstPayload));
    std::set<int> sections;
    for (const Json& p : asArray(parts)) {
      const std::string& url = p.at("url").get<std::string>();
      EXPECT_TRUE(url.starts_with("/parts/") && url.size() == 7 + 16) << url;
      if (p.contains("section")) sections.insert(static_cast<int>(p.at("section").get<double>()));
      if (p.at("kind").get<std::string>() == "section" && p.contains("section")) {
        const AssetSectionInfo& sec = summary.sections.at(static_cast<std::size_t>(p.at("section").get<double>()));
        EXPECT_EQ(p.at("offset").get<double>(), static_cast<double>(sec.offset));
      }
    }
    EXPECT_EQ(sections.size(), summary.sections.size());
    // Fetching every part and placing it at its offset rebuilds the file byte for byte.
    EXPECT_TRUE(assemble(s.port, *e) == asString(*x.bytes));
  }
}

TEST(Parts, EveryEncodingDecodesToThePartBytes) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  std::map<std::string, int> compressed;  // encoding -> parts served in it
  for (const char* file : {"room.prt", "encoded.prt"}) {
    const Json* e = entry(cat, file);
    ASSERT_NE(e, nullptr);
    const std::vector<std::uint8_t>& bytes = std::string(file) == "room.prt" ? s.tree.room : s.encoded.bytes;
    for (const Json& p : asArray(e->at("parts"))) {
      const std::string& url = p.at("url").get<std::string>();
      const std::string want = asString(bytes).substr(static_cast<std::size_t>(p.at("offset").get<double>()),
                                                      static_cast<std::size_t>(p.at("size").get<double>()));
      std::set<std::string> etags;
      for (const char* accept : {"identity", "gzip", "zstd", "br", "gzip, deflate, br, zstd"}) {
        const HttpResponse r = fetch(s.port, url, {{"Accept-Encoding", accept}});
        ASSERT_EQ(r.status, 200) << url << " " << accept;
        const std::string enc = r.header("content-encoding");
        if (std::string(accept) != "identity" && std::string(accept).find(',') == std::string::npos) {
          EXPECT_TRUE(enc.empty() || enc == accept) << url << " " << accept << " -> " << enc;
        }
        if (!enc.empty()) {
          ++compressed[enc];
          EXPECT_LT(r.body.size(), want.size()) << url << " " << enc;
        }
        EXPECT_EQ(r.header("content-length"), std::to_string(r.body.size()));
        EXPECT_TRUE(decodeAs(enc, r.body) == want) << url << " " << accept;
        etags.insert(r.header("etag"));
      }
      EXPECT_GE(etags.size(), 1u);
    }
  }
  // The transfer and mesh parts of these assets compress: every coding was used.
  EXPECT_GT(compressed["gzip"], 0);
  EXPECT_GT(compressed["zstd"], 0);
  EXPECT_GT(compressed["br"], 0);
}

TEST(Parts, ImmutableCachingValidatorsRangesAndHead) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  const Json* room = entry(cat, "room.prt");
  ASSERT_NE(room, nullptr);
  // The largest part: a transfer section, certainly compressible.
  const Json* biggest = nullptr;
  for (const Json& p : asArray(room->at("parts"))) {
    if (!biggest || p.at("size").get<double>() > biggest->at("size").get<double>()) biggest = &p;
  }
  ASSERT_NE(biggest, nullptr);
  const std::string url = biggest->at("url").get<std::string>();
  const std::string hash = url.substr(7);
  const std::string want = asString(s.tree.room).substr(static_cast<std::size_t>(biggest->at("offset").get<double>()),
                                                        static_cast<std::size_t>(biggest->at("size").get<double>()));
  EXPECT_EQ(hexHash(std::vector<std::uint8_t>(want.begin(), want.end())), hash);  // content-addressed

  const HttpResponse r = fetch(s.port, url);
  ASSERT_EQ(r.status, 200);
  EXPECT_TRUE(r.body == want);
  EXPECT_EQ(r.header("content-type"), "application/octet-stream");
  EXPECT_EQ(r.header("cache-control"), kImmutable);
  EXPECT_EQ(r.header("etag"), "\"" + hash + "\"");
  EXPECT_EQ(r.header("vary"), "Accept-Encoding");
  EXPECT_EQ(r.header("accept-ranges"), "bytes");
  EXPECT_EQ(r.header("x-content-type-options"), "nosniff");

  const HttpResponse br = fetch(s.port, url, {{"Accept-Encoding", "br"}});
  ASSERT_EQ(br.header("content-encoding"), "br");
  EXPECT_EQ(br.header("etag"), "\"" + hash + ".br\"");
  EXPECT_EQ(br.header("cache-control"), kImmutable);

  // Revalidation: each representation by its own validator.
  const HttpResponse notModified = fetch(s.port, url, {{"If-None-Match", r.header("etag")}});
  EXPECT_EQ(notModified.status, 304);
  EXPECT_TRUE(notModified.body.empty());
  EXPECT_EQ(notModified.header("cache-control"), kImmutable);
  EXPECT_EQ(fetch(s.port, url, {{"If-None-Match", br.header("etag")}, {"Accept-Encoding", "br"}}).status, 304);
  EXPECT_EQ(fetch(s.port, url, {{"If-None-Match", br.header("etag")}}).status, 200);
  EXPECT_EQ(fetch(s.port, url, {{"If-None-Match", "\"0000000000000000\""}}).status, 200);

  const HttpResponse head = fetch(s.port, url, {}, "HEAD");
  EXPECT_EQ(head.status, 200);
  EXPECT_TRUE(head.body.empty());
  EXPECT_EQ(head.header("content-length"), std::to_string(want.size()));
  EXPECT_EQ(head.header("etag"), r.header("etag"));

  const HttpResponse range = fetch(s.port, url, {{"Range", "bytes=10-99"}});
  EXPECT_EQ(range.status, 206);
  EXPECT_TRUE(range.body == want.substr(10, 90));
  EXPECT_EQ(range.header("content-range"), "bytes 10-99/" + std::to_string(want.size()));
  EXPECT_EQ(fetch(s.port, url, {{"Range", "bytes=" + std::to_string(want.size()) + "-"}}).status, 416);
}

TEST(Parts, EncodedTransferIsCutAtBandBoundaries) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  const Json* e = entry(cat, "encoded.prt");
  ASSERT_NE(e, nullptr);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(s.encoded.bytes, &summary).isOk());
  const int order = s.encoded.order;
  for (const auto& [pass, blob, clusters] :
       {std::tuple{std::string("interreflected"), &s.encoded.cpcaBlob, true},
        std::tuple{std::string("shadowed"), &s.encoded.quantBlob, false}}) {
    SCOPED_TRACE(pass);
    std::vector<const Json*> mine;
    for (const Json& p : asArray(e->at("parts"))) {
      if (p.value("pass", "") == pass) mine.push_back(&p);  // parts outside a transfer have no pass
    }
    ASSERT_EQ(mine.size(), static_cast<std::size_t>(1 + (clusters ? 1 : 0) + order));
    const int section = static_cast<int>(mine[0]->at("section").get<double>());
    EXPECT_EQ(summary.sections.at(static_cast<std::size_t>(section)).type,
              static_cast<std::uint32_t>(AssetSectionType::kEncodedTransfer));
    EXPECT_EQ(mine[0]->at("offset").get<double>(), static_cast<double>(summary.sections[static_cast<std::size_t>(section)].offset));
    std::size_t k = 0;
    EXPECT_EQ(mine[k++]->at("kind").get<std::string>(), "transfer-head");
    if (clusters) {
      EXPECT_EQ(mine[k++]->at("kind").get<std::string>(), "transfer-clusters");
    }
    for (int l = 0; l < order; ++l, ++k) {
      EXPECT_EQ(mine[k]->at("kind").get<std::string>(), "transfer-band");
      EXPECT_EQ(mine[k]->at("band").get<double>(), l);
      EXPECT_EQ(mine[k]->at("section").get<double>(), section);
    }
    // A progressive client: blob head (+ clusters), then band after band, decoding as it
    // goes; each prefix decodes like the whole blob at that many bands.
    std::vector<std::uint8_t> prefix;
    for (std::size_t i = 0; i < mine.size(); ++i) {
      const HttpResponse r = fetch(s.port, mine[i]->at("url").get<std::string>(), {{"Accept-Encoding", "br, gzip"}});
      ASSERT_EQ(r.status, 200);
      const std::string bytes = decodeAs(r.header("content-encoding"), r.body);
      prefix.insert(prefix.end(), bytes.begin(), bytes.end());
      if (mine[i]->at("kind").get<std::string>() != "transfer-band") continue;
      const int bands = static_cast<int>(mine[i]->at("band").get<double>()) + 1;
      std::vector<std::uint8_t> usable = prefix;
      if (bands == order) usable.resize(blob->size());  // the section's padding follows the blob
      std::vector<float> got, want;
      const Status st = decodeTransfer(usable, bands, &got);
      ASSERT_TRUE(st.isOk()) << bands << " bands: " << st.toString();
      ASSERT_TRUE(decodeTransfer(*blob, bands, &want).isOk());
      EXPECT_TRUE(got == want) << bands << " bands";
    }
  }
}

// Transfer textures in the catalogue: every pass names its domain, the entry its texel
// count; the texel pass's parts and the atlas sections' say "domain":"texel" (a client that
// renders vertex passes only skips them), the vertex passes' parts "domain":"vertex".
TEST(Parts, TexelPassesAndAtlasSectionsAreMarkedInTheCatalogue) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  const Json* e = entry(cat, "texel.prt");
  ASSERT_NE(e, nullptr);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(s.texel.bytes, &summary).isOk());
  EXPECT_EQ(e->at("version").get<std::string>(), "1.7");
  EXPECT_EQ(e->at("texels").get<double>(), static_cast<double>(summary.texelCount));
  const Json& passes = e->at("passes");
  ASSERT_EQ(asArray(passes).size(), summary.passes.size());
  for (std::size_t i = 0; i < summary.passes.size(); ++i) {
    EXPECT_EQ(passes.at(i).at("domain").get<std::string>(), transferDomainName(summary.passes[i].domain)) << i;
    EXPECT_EQ(passes.at(i).at("kind").get<std::string>(), transferKindName(summary.passes[i].kind)) << i;
  }
  int texelParts = 0, texelBands = 0;
  for (const Json& p : asArray(e->at("parts"))) {
    if (!p.contains("section")) {
      EXPECT_FALSE(p.contains("domain"));  // the head
      continue;
    }
    const std::uint32_t type = summary.sections.at(static_cast<std::size_t>(p.at("section").get<double>())).type;
    const bool texel = type >= static_cast<std::uint32_t>(AssetSectionType::kAtlasUv);
    const bool pass = p.contains("pass");
    if (texel) {
      EXPECT_EQ(p.value("domain", ""), "texel") << "section type " << type;
      ++texelParts;
      if (p.at("kind").get<std::string>() == "transfer-band") ++texelBands;
    } else if (pass) {
      EXPECT_EQ(p.value("domain", ""), "vertex") << "section type " << type;
    } else {
      EXPECT_FALSE(p.contains("domain")) << "section type " << type;  // geometry and metadata
    }
  }
  EXPECT_EQ(texelBands, s.texel.order);
  EXPECT_EQ(texelParts, 3 + 1 + s.texel.order);  // uv, atlases, coverage; blob head and bands
}

// The visibility pass says what it is, so a client without a TPFL shader can skip it and not
// mistake it for the texel shadowed vector pass of the same kind and domain.
TEST(Parts, VisibilityPassIsMarkedInTheCatalogueAndItsParts) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  const Json* e = entry(cat, "visibility.prt");
  ASSERT_NE(e, nullptr);
  int listed = 0;
  for (const Json& p : asArray(e->at("passes"))) {
    if (p.value("form", "vector") != "visibility") continue;
    ++listed;
    EXPECT_EQ(p.at("kind").get<std::string>(), "shadowed");
    EXPECT_EQ(p.at("domain").get<std::string>(), "texel");
    EXPECT_EQ(p.at("order").get<double>(), 2.0 * s.visibility.order - 1.0);
  }
  EXPECT_EQ(listed, 1);
  int bands = 0, vectorTexelBands = 0;
  for (const Json& p : asArray(e->at("parts"))) {
    if (p.value("kind", "") != "transfer-band" || p.value("domain", "") != "texel") continue;
    if (p.value("form", "vector") == "visibility") ++bands;
    else ++vectorTexelBands;
  }
  EXPECT_EQ(bands, 2 * s.visibility.order - 1);
  EXPECT_EQ(vectorTexelBands, s.visibility.order);
}

TEST(Parts, IdenticalPartsShareOneUrl) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  const Json* room = entry(cat, "room.prt");
  const Json* twin = entry(cat, "twin.prt");
  ASSERT_NE(room, nullptr);
  ASSERT_NE(twin, nullptr);
  std::set<std::string> roomUrls;
  for (const Json& p : asArray(room->at("parts"))) roomUrls.insert(p.at("url").get<std::string>());
  // Only the name differs: the head (sizes in the table) and the metadata differ, the
  // mesh and transfer parts are the same bytes at the same URLs.
  int shared = 0, own = 0;
  for (const Json& p : asArray(twin->at("parts"))) (roomUrls.count(p.at("url").get<std::string>()) ? shared : own)++;
  EXPECT_EQ(own, 2);
  EXPECT_EQ(shared, static_cast<int>(asArray(twin->at("parts")).size()) - 2);
}

TEST(Parts, BadPartUrlsAre404Or400) {
  PartsServer& s = partsServer();
  const Json cat = catalogue(s.port);
  const Json* room = entry(cat, "room.prt");
  ASSERT_NE(room, nullptr);
  const std::string good = room->at("parts").at(1).at("url").get<std::string>();
  std::string upper = good;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  upper.replace(0, 7, "/parts/");
  for (const std::string& target :
       {std::string("/parts/0000000000000000"), std::string("/parts/"), std::string("/parts"), upper,
        good + "/x", good + ".br", good + "0", good.substr(0, good.size() - 1), "/parts/" + hexHash(s.tree.room),
        "/parts/" + hexHash(s.tree.room) + "/room.prt", good + "?v=2"}) {
    const HttpResponse r = fetch(s.port, target);
    if (target.find('?') != std::string::npos) {
      EXPECT_EQ(r.status, 200) << target;  // a query does not change what a path names
      continue;
    }
    EXPECT_EQ(r.status, 404) << target;
    EXPECT_LT(r.body.size(), 200u) << target;
  }
  for (const std::string& target : {std::string("/parts/../assets"), std::string("/parts/%2e%2e/%2e%2e/etc/passwd"),
                                    std::string("/parts/..%2f..%2fetc%2fpasswd"), good + "%00",
                                    std::string("/parts//") + good.substr(7), std::string("/parts/%5c..")}) {
    const RawResult r = rawExchange(s.port, "GET " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
                                    std::chrono::seconds(5));
    const int status = rawStatus(r.received);
    EXPECT_TRUE(status == 400 || status == 404) << target << " -> " << r.received.substr(0, 120);
    EXPECT_EQ(r.received.find("root:x:0"), std::string::npos);
    EXPECT_TRUE(healthy(s.port)) << "after " << target;
  }
  EXPECT_EQ(fetch(s.port, "/parts/0000000000000000", {}, "HEAD").status, 404);
  EXPECT_EQ(fetch(s.port, good, {}, "POST").status, 405);
}

TEST(Parts, LimitLeavesLargerAssetsWhole) {
  const TestTree tree = makeTestTree(workDir());
  auto limited = startServer(tree, {"--max-parts-mib", "1"}, "parts-limit.log");
  ASSERT_TRUE(limited);
  const Json cat = catalogue(limited->port());
  ASSERT_GT(tree.room.size(), 1u << 20);
  const Json* room = entry(cat, "room.prt");
  const Json* small = entry(cat, "sub/small.prt");
  ASSERT_NE(room, nullptr);
  ASSERT_NE(small, nullptr);
  EXPECT_TRUE(room->at("usable").get<bool>());
  EXPECT_FALSE(room->contains("parts"));  // over the limit: the client takes the whole asset
  EXPECT_EQ(fetch(limited->port(), room->at("url").get<std::string>()).status, 200);
  ASSERT_TRUE(small->contains("parts"));
  EXPECT_TRUE(assemble(limited->port(), *small) == asString(tree.small));
  // The room's parts, served by a server without a limit, do not exist here.
  PartsServer& s = partsServer();
  const Json full = catalogue(s.port);
  const Json* fullRoom = entry(full, "room.prt");
  ASSERT_NE(fullRoom, nullptr);
  const std::string roomPart = fullRoom->at("parts").at(1).at("url").get<std::string>();
  EXPECT_EQ(fetch(s.port, roomPart).status, 200);
  EXPECT_EQ(fetch(limited->port(), roomPart).status, 404);
  EXPECT_EQ(limited->stop(SIGTERM, std::chrono::seconds(20)), 0);

  auto none = startServer(tree, {"--max-parts-mib", "0"}, "parts-none.log");
  ASSERT_TRUE(none);
  const Json unparted = catalogue(none->port());
  ASSERT_FALSE(asArray(unparted.at("scenes")).empty());
  for (const Json& e : asArray(unparted.at("scenes"))) EXPECT_FALSE(e.contains("parts")) << e.at("file").get<std::string>();
  EXPECT_EQ(none->stop(SIGTERM, std::chrono::seconds(20)), 0);
}

TEST(Parts, PartsFollowTheCatalogue) {
  const TestTree tree = makeTestTree(workDir());
  const std::vector<std::uint8_t> twin = makeAssetBytes(6000, 4, 1, "twin of the room");
  writeFile(tree.root + "/twin.prt", twin);
  auto server = startServer(tree, {}, "parts-rescan.log");
  ASSERT_TRUE(server);
  const int port = server->port();
  const Json before = catalogue(port);
  const Json* roomBefore = entry(before, "room.prt");
  const Json* twinBefore = entry(before, "twin.prt");
  ASSERT_NE(roomBefore, nullptr);
  ASSERT_NE(twinBefore, nullptr);
  std::set<std::string> roomUrls;
  for (const Json& p : asArray(roomBefore->at("parts"))) roomUrls.insert(p.at("url").get<std::string>());
  std::vector<std::string> twinOnly, twinShared;
  for (const Json& p : asArray(twinBefore->at("parts"))) {
    (roomUrls.count(p.at("url").get<std::string>()) ? twinShared : twinOnly).push_back(p.at("url").get<std::string>());
  }
  ASSERT_EQ(twinOnly.size(), 2u);
  ASSERT_FALSE(twinShared.empty());
  for (const std::string& u : twinOnly) EXPECT_EQ(fetch(port, u).status, 200);

  // The twin is deleted: its own parts go with it, the parts it shares with the room stay.
  ASSERT_EQ(std::remove((tree.root + "/twin.prt").c_str()), 0);
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i) {
    gone = entry(catalogue(port), "twin.prt") == nullptr;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(gone);
  for (const std::string& u : twinOnly) EXPECT_EQ(fetch(port, u).status, 404) << u;
  for (const std::string& u : twinShared) EXPECT_EQ(fetch(port, u).status, 200) << u;
  EXPECT_EQ(server->stop(SIGTERM, std::chrono::seconds(20)), 0);
}

}  // namespace
}  // namespace prt::serve::test
