// Mapping helpers (see huge_pages.hpp). Linux: madvise(MADV_HUGEPAGE) for transparent huge pages,
// madvise(MADV_POPULATE_WRITE) to map 4 KiB pages in one call, mmap for HugeBuffer (its own mapping,
// 2 MiB-aligned by over-mapping and trimming). Advice errors (THP disabled, old kernels) are ignored:
// the advice is optional. Elsewhere: plain operator new and no advice.
#include <volmap/core/huge_pages.hpp>

#include <cstdint>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace volmap {
namespace {

constexpr std::uintptr_t kPage = 4096;
// glibc's chunk header before the storage of a block it maps on its own, and its size rounding: a
// request of k·2 MiB − kMallocOverhead bytes becomes a mapping of exactly k·2 MiB, data at +16.
constexpr std::size_t kMallocOverhead = 24;
constexpr std::size_t kMallocHeader = 16;

std::size_t round_up_huge(std::size_t bytes) { return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes; }

#if defined(__linux__)
void advise_huge(void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  (void)madvise(p, bytes, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}
#endif

}  // namespace

bool huge_pages_worthwhile(std::size_t bytes) noexcept {
  return bytes >= (std::size_t(1) << 20) && round_up_huge(bytes) - bytes <= bytes / 3;
}

void populate_pages(void* p, std::size_t bytes) noexcept {
#if defined(__linux__)
#ifndef MADV_POPULATE_WRITE
  constexpr int MADV_POPULATE_WRITE = 23;  // Linux 5.14
#endif
  if (p == nullptr || bytes < 16 * kPage) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + kPage - 1) & ~(kPage - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kPage - 1);
  if (last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
#else
  (void)p, (void)bytes;
#endif
}

std::size_t huge_page_capacity(std::size_t n, std::size_t element_bytes) noexcept {
  const std::size_t whole = round_up_huge(n * element_bytes + kMallocOverhead);
  return (whole - kMallocOverhead) / element_bytes;
}

void advise_vector_storage(const void* data, std::size_t capacity_bytes) noexcept {
#if defined(__linux__)
  const auto chunk = reinterpret_cast<std::uintptr_t>(data) - kMallocHeader;
  if (chunk % kHugePageBytes != 0) return;  // not its own aligned mapping: leave it to 4 KiB pages
  const std::size_t size = round_up_huge(capacity_bytes + kMallocOverhead);
  advise_huge(reinterpret_cast<void*>(chunk), size);
  // glibc has written its chunk header already, so the first 4 KiB page is mapped and a fault would
  // no longer install a huge page there: collapse the (almost empty) range into huge pages now.
#ifndef MADV_COLLAPSE
  constexpr int MADV_COLLAPSE = 25;  // Linux 6.1
#endif
  (void)madvise(reinterpret_cast<void*>(chunk), size, MADV_COLLAPSE);
#else
  (void)data, (void)capacity_bytes;
#endif
}

void* map_buffer(std::size_t bytes) {
#if defined(__linux__)
  if (huge_pages_worthwhile(bytes)) {
    const std::size_t size = round_up_huge(bytes);
    // Over-map by one huge page, then trim both ends to a 2 MiB-aligned block.
    void* raw = mmap(nullptr, size + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const auto begin = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (begin + kHugePageBytes - 1) & ~(std::uintptr_t(kHugePageBytes) - 1);
    if (aligned > begin) munmap(raw, aligned - begin);
    const std::uintptr_t tail = begin + size + kHugePageBytes - (aligned + size);
    if (tail > 0) munmap(reinterpret_cast<void*>(aligned + size), tail);
    void* p = reinterpret_cast<void*>(aligned);
    advise_huge(p, size);
    populate_pages(p, size);
    return p;
  }
#endif
  void* p = ::operator new(bytes);
  populate_pages(p, bytes);
  return p;
}

void unmap_buffer(void* p, std::size_t bytes) noexcept {
#if defined(__linux__)
  if (huge_pages_worthwhile(bytes)) {
    munmap(p, round_up_huge(bytes));
    return;
  }
#endif
  ::operator delete(p);
}

}  // namespace volmap
