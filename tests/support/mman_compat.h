// Page-granular memory for the tests (guard pages, no-access pages, a
// read-only page after an array): POSIX mmap / mprotect / munmap and
// sysconf(_SC_PAGESIZE) on Linux, and the same calls on Windows (the wine
// run of the suite) written over VirtualAlloc / VirtualProtect /
// VirtualFree, so the tests keep one spelling.
//
// The Windows versions cover what the tests use and nothing more:
// anonymous private mappings (fd -1), protection changes on whole pages,
// and munmap of a whole mapping at its base. A request outside that
// (a file mapping, MAP_FIXED, a partial unmap) fails with MAP_FAILED / -1,
// so a test that needs it fails loudly instead of testing something else.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#if !defined(_WIN32)
#include <sys/mman.h>
#include <unistd.h>
#else
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>

#include <cstddef>

#define PROT_NONE 0
#define PROT_READ 1
#define PROT_WRITE 2
#define MAP_PRIVATE 0x02
#define MAP_FIXED 0x10
#define MAP_ANONYMOUS 0x20
#define MAP_NORESERVE 0x4000
#define MAP_FAILED ((void *)-1)
#ifndef _SC_PAGESIZE
#define _SC_PAGESIZE 30
#endif

namespace svtest_win {

inline DWORD page_protection(int prot) {
    if (prot & PROT_WRITE) return PAGE_READWRITE;
    if (prot & PROT_READ) return PAGE_READONLY;
    return PAGE_NOACCESS;
}

} // namespace svtest_win

// A hint address is honoured when that range is free (VirtualAlloc at
// it), otherwise the system chooses, as Linux does without MAP_FIXED.
inline void *mmap(void *hint, size_t len, int prot, int flags, int fd, long off) {
    if (fd != -1 || off != 0 || !(flags & MAP_ANONYMOUS) || (flags & MAP_FIXED)) {
        return MAP_FAILED;
    }
    const DWORD protect = svtest_win::page_protection(prot);
    void *p = hint ? VirtualAlloc(hint, len, MEM_RESERVE | MEM_COMMIT, protect) : nullptr;
    if (!p) p = VirtualAlloc(nullptr, len, MEM_RESERVE | MEM_COMMIT, protect);
    return p ? p : MAP_FAILED;
}

inline int mprotect(void *addr, size_t len, int prot) {
    DWORD old;
    return VirtualProtect(addr, len, svtest_win::page_protection(prot), &old) ? 0 : -1;
}

inline int munmap(void *addr, size_t) { return VirtualFree(addr, 0, MEM_RELEASE) ? 0 : -1; }

// sysconf under this name is what the tests call; only the page size.
inline long svtest_sysconf(int name) {
    if (name != _SC_PAGESIZE) return -1;
    SYSTEM_INFO si;
    GetSystemInfo(&si);
    return (long)si.dwPageSize;
}
#define sysconf svtest_sysconf
#endif
