#include "dir_scan.h"

#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <set>
#include <utility>

namespace prt::serve {
namespace {

bool hasExtension(std::string_view name, std::span<const std::string_view> extensions) {
  for (std::string_view ext : extensions) {
    if (name.size() <= ext.size()) continue;
    const std::string_view tail = name.substr(name.size() - ext.size());
    bool same = true;
    for (std::size_t i = 0; i < ext.size() && same; ++i) {
      same = std::tolower(static_cast<unsigned char>(tail[i])) == ext[i];
    }
    if (same) return true;
  }
  return false;
}

struct DirCloser {
  void operator()(DIR* d) const { ::closedir(d); }
};

std::string realPath(const std::string& path) {
  std::unique_ptr<char, decltype(&::free)> real(::realpath(path.c_str(), nullptr), &::free);
  return real ? std::string(real.get()) : std::string();
}

struct Walker {
  const RootDir& root;
  std::span<const std::string_view> extensions;
  ScanLimits limits;
  std::vector<ScannedFile> out;
  std::set<std::pair<std::uint64_t, std::uint64_t>> visited;  // (device, inode) of directories

  void walk(const std::string& absDir, const std::string& relDir, int depth) {
    std::unique_ptr<DIR, DirCloser> dir(::opendir(absDir.c_str()));
    if (!dir) return;
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(dir.get())) {
      if (e->d_name[0] == '.') continue;  // ".", "..", and hidden files
      names.emplace_back(e->d_name);
    }
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
      if (out.size() >= limits.maxFiles) return;
      const std::string abs = absDir + "/" + name;
      const std::string rel = relDir.empty() ? name : relDir + "/" + name;
      struct stat lst {};
      if (::lstat(abs.c_str(), &lst) != 0) continue;
      const bool matches = hasExtension(name, extensions);
      struct stat st = lst;
      if (S_ISLNK(lst.st_mode)) {
        const std::string target = realPath(abs);
        if (target.empty() || ::stat(abs.c_str(), &st) != 0) continue;  // dangling
        if (!root.contains(target)) {
          if (matches && S_ISREG(st.st_mode)) out.push_back({rel, abs, {}, "symlink leads outside the root"});
          continue;
        }
      }
      if (S_ISDIR(st.st_mode)) {
        if (depth >= limits.maxDepth) continue;
        if (!visited.insert({static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)}).second) {
          continue;  // a loop, or a second way into a directory already listed
        }
        walk(abs, rel, depth + 1);
      } else if (S_ISREG(st.st_mode) && matches) {
        out.push_back({rel, abs, stampOf(st), {}});
      }
    }
  }
};

}  // namespace

std::vector<ScannedFile> scanDirectory(const RootDir& root, std::span<const std::string_view> extensions,
                                       const ScanLimits& limits) {
  Walker w{root, extensions, limits, {}, {}};
  struct stat st {};
  if (::stat(root.path().c_str(), &st) == 0) {
    w.visited.insert({static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)});
  }
  w.walk(root.path() == "/" ? std::string() : root.path(), "", 0);
  std::sort(w.out.begin(), w.out.end(), [](const ScannedFile& a, const ScannedFile& b) { return a.relPath < b.relPath; });
  return w.out;
}

}  // namespace prt::serve
