// seam-bench: `seam-bench <benchmark> [options]`, `seam-bench --help`.
#include "registry.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>

namespace {

void usage(std::FILE* out) {
  std::fprintf(out, "usage: seam-bench <benchmark> [options]   (seam-bench <benchmark> --help)\n"
                    "benchmarks:\n");
  auto all = seam::bench::commands();
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  for (const auto& c : all) std::fprintf(out, "  %-12s %s\n", c.name.c_str(), c.summary.c_str());
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 1 : 0;
  }
  for (const auto& c : seam::bench::commands()) {
    if (c.name != argv[1]) continue;
    try {
      return c.run(argc - 1, argv + 1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "seam-bench %s: %s\n", argv[1], e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "seam-bench: unknown benchmark '%s'\n", argv[1]);
  usage(stderr);
  return 1;
}
