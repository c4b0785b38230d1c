// Measures what the first write to fresh memory costs on this machine: page by page (one page
// fault per 4 KiB page) against growth::prefault (one madvise(MADV_POPULATE_WRITE) call for the
// range), on a fresh 64 MiB anonymous mapping each time, fastest of 3: the costs that
// growth/huge_pages.h weighs.
//
//   fault_cost [MiB]
#include <growth/huge_pages.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

int main(int argc, char** argv) {
#if defined(__linux__)
  const size_t mib = argc > 1 ? size_t(std::strtoul(argv[1], nullptr, 10)) : 64;
  const size_t bytes = mib << 20, page = size_t(sysconf(_SC_PAGESIZE));
  auto run = [&](bool populate) {
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      void* raw = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (raw == MAP_FAILED) return -1.0;
      auto* p = static_cast<volatile char*>(raw);
      const auto t0 = std::chrono::steady_clock::now();
      if (populate && !growth::prefault(raw, bytes)) {
        munmap(raw, bytes);
        return -1.0;
      }
      for (size_t i = 0; i < bytes; i += page) p[i] = 1;
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      munmap(raw, bytes);
      if (s < best) best = s;
    }
    return best;
  };
  const double faults = run(false), populated = run(true);
  std::printf("page by page: %.2f ms/MiB (%.1f us per %zu-byte page)\n", faults * 1e3 / double(mib),
              faults * 1e6 / double(bytes / page), page);
  if (populated < 0)
    std::printf("prefault: not available here (MADV_POPULATE_WRITE needs Linux 5.14)\n");
  else
    std::printf("prefault: %.2f ms/MiB\n", populated * 1e3 / double(mib));
  return 0;
#else
  (void)argc;
  (void)argv;
  std::printf("fault_cost: Linux only\n");
  return 0;
#endif
}
