// Progressive loading of an asset that arrives in parts (prt-serve's /parts/, docs/server.md):
// the file-sized buffer the parts are placed into, its validated header and table, and the
// decoding of the geometry and of each transfer pass at the bands that have arrived.
// GL-free; every byte is checked by the shared reader (checksums per section and per band).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/asset.h"
#include "prt/status.h"

namespace prt::web {

class AssetStream {
 public:
  // A zeroed buffer of `bytes` (the catalogue's file size) for the parts; nullptr when it
  // cannot be allocated. Forgets any previous stream.
  std::uint8_t* reserve(std::size_t bytes);
  std::uint8_t* data() { return file_.data(); }
  std::size_t size() const { return file_.size(); }

  // Once the head part and every non-transfer section (the atlas sections included) have been
  // placed: validates header, table, metadata and lighting (peekAssetHeader), checks that the
  // declared file size is the buffer's, and decodes the geometry (no passes) into *out, with
  // the atlas uv, atlases and texel coverage when the asset has texel passes.
  Status decodeGeometry(BakedAsset* out);

  // Decodes the pass of `kind` (0 unshadowed, 1 shadowed, 2 interreflected) from its first
  // `bands` bands (0: the whole pass, the only choice for a float32 pass). The caller says
  // which bands have arrived; the bands' own checksums catch a wrong claim. *order is the
  // order of the decoded transfer. Requires decodeGeometry first.
  Status decodePass(int kind, int bands, TransferPass* out, int* order);

  // The same pass unexpanded, for rendering straight from CPCA (decodeAssetPassCpca): *info
  // gets kind and channels. kInvalidArgument when the pass is not CPCA-encoded.
  Status decodePassCpca(int kind, int bands, CpcaTransfer* out, TransferPass* info);
  // Whether pass `kind` is CPCA-encoded, read from its blob's header (which arrives with the
  // pass's first part): false before then, for other encodings and for float32 passes.
  bool isCpca(int kind) const;
  // The same for the matrix pass of `kind`.
  bool isMatrixCpca(int kind) const;
  // The matrix pass of `kind` expanded (decodeAssetPass): *order its bands.
  Status decodeMatrixPass(int kind, int bands, TransferPass* out, int* order);

  // Whether the asset holds a (vector, vertex) pass of `kind`.
  bool hasKind(int kind) const;
  // Whether the asset holds a texel pass (transfer textures) of `kind`.
  bool hasTexelKind(int kind) const;
  // The texel pass of `kind` from its first `bands` bands (0: whole; float32 passes decode
  // only whole; a CPCA-encoded one is expanded): texels x channels x order^2 floats.
  Status decodeTexelPass(int kind, int bands, TransferPass* out, int* order);

  // Glossy: the matrix pass of `kind` unexpanded (decodeAssetPassCpcaMatrix) from its first
  // `bands` shells (0: every shell that has arrived); kInvalidArgument when absent or not CPCA.
  Status decodeMatrixPassCpca(int kind, int bands, CpcaMatrixTransfer* out, TransferPass* info);
  // Whether the asset holds a matrix pass of `kind`.
  bool hasMatrixKind(int kind) const;
  // Whether the asset has a TPFL texel visibility pass (form kVisibility; at most one is used).
  bool hasVisibility() const;
  // Decodes that pass from its first `bands` bands (0: all; float32 passes only decode
  // whole); *order gets the bands decoded. Errors: no geometry decoded yet, no such pass, or
  // the reader's (checksums, truncation).
  Status decodeVisibilityPass(int bands, TransferPass* out, int* order);
  // The specular materials (their section must have arrived; empty without a matrix pass).
  Status decodeSpecular(std::vector<SpecularMaterial>* out);
  const AssetSummary& summary() const { return summary_; }
  void release();  // frees the buffer (the decoded arrays live elsewhere)

 private:
  std::vector<std::uint8_t> file_;
  AssetSummary summary_;
  bool headerRead_ = false;
  // Index into summary_.passes of the pass of `kind`, `form` and `domain`, or -1.
  int passIndex(int kind, TransferForm form = TransferForm::kVector, TransferDomain domain = TransferDomain::kVertex) const;
  int visibilityIndex() const;  // the first kVisibility pass, or -1
  bool isCpcaAt(int index) const;
};

}  // namespace prt::web
