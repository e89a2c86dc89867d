/*
 * The data caches of the CPU the bench runs on: the sizes the scaling run
 * marks on its plot and the cycle table uses to size its batches.
 *
 * Two sources, per level: glibc's sysconf(_SC_LEVEL1_DCACHE_SIZE,
 * _SC_LEVEL2_CACHE_SIZE, _SC_LEVEL3_CACHE_SIZE), which reads CPUID, and,
 * where it answers 0 or -1 (other libcs, some hypervisors' CPUID), the
 * kernel's /sys/devices/system/cpu/cpu0/cache/indexN/{level,type,size}.
 *
 * What the numbers mean is the hardware's report, not what one core may
 * use: an L3 shared by several cores, or split into slices (an AMD EPYC's
 * L3 is one slice per CCD), is reported whole by some CPUs and hypervisors.
 * The reports print the size with its source and say so.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_CACHE_INFO_H
#define SV_BENCH_CACHE_INFO_H

#include <cstddef>
#include <string>

namespace svbench {

struct CacheLevel {
    const char *name = "";   /* "L1D", "L2", "L3" */
    size_t bytes = 0;        /* 0: unknown */
    const char *source = ""; /* "sysconf", "sysfs", "" when unknown */
};

struct CacheSizes {
    CacheLevel l1d, l2, l3;
    /* The three in order, for loops. */
    const CacheLevel *begin() const { return &l1d; }
    const CacheLevel *end() const { return &l3 + 1; }
};

/* Read once; the same answer for the whole process. */
const CacheSizes &cache_sizes();

/* "48 KiB", "1 MiB", "508 MiB", "1.5 MiB": binary units, at most one
 * decimal, "unknown" for 0. */
std::string format_bytes(double bytes);

/* "L1D 48 KiB, L2 1 MiB, L3 508 MiB (sysconf)", naming each source that
 * differs and every unknown level. */
std::string cache_summary(const CacheSizes &c);

/* Parses a sysfs cache size ("48K", "1024K", "32M", "512"): bytes, or 0
 * when the text is not one. Exposed for the tests. */
size_t parse_sysfs_size(const std::string &text);

} // namespace svbench

#endif
