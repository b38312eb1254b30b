#pragma once
// Large blocks in transparent huge pages, for a process that makes and frees its solver over and over.
// A distributed run makes each rank's solver afresh at every halo build and moves its lazy rows through
// a buffer of the same size (DistributedRun::build_local): hundreds of MB of new pages each time, and in
// 4 kB pages their first touch costs more than the build's own work (page faults were 40 % of a rank's
// time on the shipped disc; docs/studies/2026-12-07-distributed-shot.md). Once enabled, every block of
// at least 4 MB that the program's operator new gets from malloc is advised MADV_HUGEPAGE, as glibc's
// glibc.malloc.hugetlb=1 tunable does for its own large chunks; the kernel then backs its 2 MB-aligned
// part with huge pages where its THP setting allows it (madvise or always; under never it is a no-op).
// It is advice: the values computed never change. Off until enabled, so a one-process run, which
// allocates its solver once and gains nothing from it (measured), allocates as it always did.
// huge_pages.cpp replaces the global operator new and delete of any program that links it: with the
// advice off they are malloc (with the standard's new-handler loop) and free, as the library's own.
namespace uhpc::macro::distributed {

// For the rest of the process. Idempotent; safe from any thread.
void advise_huge_pages_for_large_blocks();

}  // namespace uhpc::macro::distributed
