// prt_serve_make_asset OUT VERTICES ORDER: writes a synthetic but valid asset (the tests'
// generator), for the server benchmark's "1 MB asset".
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "test_tree.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: prt_serve_make_asset OUT VERTICES ORDER\n");
    return 2;
  }
  try {
    const auto bytes = prt::serve::test::makeAssetBytes(std::atoi(argv[2]), std::atoi(argv[3]), 1, "bench asset");
    prt::serve::test::writeFile(argv[1], bytes);
    std::printf("%zu\n", bytes.size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_serve_make_asset: %s\n", e.what());
    return 1;
  }
}
