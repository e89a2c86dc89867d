/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "cache_info.h"

#include <cstdint>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

namespace svbench {

namespace {

/* sysconf's answer for NAME: bytes, or 0 where it does not know (glibc
 * returns 0 for a level CPUID does not describe, -1 for a name it lacks). */
size_t from_sysconf(int name) {
    const long v = sysconf(name);
    return v > 0 ? (size_t)v : 0;
}

std::string read_line(const std::string &path) {
    std::ifstream f(path);
    std::string s;
    if (!f || !std::getline(f, s)) {
        return std::string();
    }
    while (!s.empty() && std::isspace((unsigned char)s.back())) {
        s.pop_back();
    }
    return s;
}

/* The size of the first cache of LEVEL that holds data ("Data" or
 * "Unified"; an "Instruction" cache is not what the kernels stream
 * through) among cpu0's index0, index1, ... */
size_t from_sysfs(int level) {
    for (int i = 0; i < 16; i++) {
        const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(i);
        const std::string lv = read_line(dir + "/level");
        if (lv.empty()) {
            break; /* indices are contiguous */
        }
        const std::string type = read_line(dir + "/type");
        if (lv == std::to_string(level) && (type == "Data" || type == "Unified")) {
            return parse_sysfs_size(read_line(dir + "/size"));
        }
    }
    return 0;
}

CacheLevel detect(const char *name, int sysconfName, int level) {
    CacheLevel c;
    c.name = name;
    if ((c.bytes = from_sysconf(sysconfName)) != 0) {
        c.source = "sysconf";
    } else if ((c.bytes = from_sysfs(level)) != 0) {
        c.source = "sysfs";
    }
    return c;
}

CacheSizes detect_all() {
    CacheSizes c;
    c.l1d = detect("L1D", _SC_LEVEL1_DCACHE_SIZE, 1);
    c.l2 = detect("L2", _SC_LEVEL2_CACHE_SIZE, 2);
    c.l3 = detect("L3", _SC_LEVEL3_CACHE_SIZE, 3);
    return c;
}

} // namespace

size_t parse_sysfs_size(const std::string &text) {
    /* 64-bit arithmetic whatever size_t is (32 bits on 32-bit x86). */
    size_t i = 0;
    uint64_t v = 0;
    while (i < text.size() && std::isdigit((unsigned char)text[i])) {
        if (v > ((uint64_t)1 << 40)) {
            return 0; /* no cache is a terabyte: not a size */
        }
        v = v * 10 + (uint64_t)(text[i++] - '0');
    }
    if (i == 0) {
        return 0;
    }
    uint64_t unit = 1;
    if (i < text.size()) {
        switch (text[i++]) {
        case 'K': unit = (uint64_t)1 << 10; break;
        case 'M': unit = (uint64_t)1 << 20; break;
        case 'G': unit = (uint64_t)1 << 30; break;
        default: return 0;
        }
    }
    const uint64_t bytes = v * unit;
    if (i != text.size() || bytes > (uint64_t)SIZE_MAX) {
        return 0;
    }
    return (size_t)bytes;
}

const CacheSizes &cache_sizes() {
    static const CacheSizes c = detect_all();
    return c;
}

std::string format_bytes(double bytes) {
    if (!(bytes > 0)) {
        return "unknown";
    }
    static const char *const units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (bytes >= 1024 && u < 4) {
        bytes /= 1024;
        u++;
    }
    char s[32];
    /* Whole numbers as such ("48 KiB"); else one decimal ("1.5 MiB"). */
    const double rounded = (double)std::llround(bytes * 10) / 10;
    if (rounded == (double)(long long)rounded) {
        std::snprintf(s, sizeof s, "%lld %s", (long long)rounded, units[u]);
    } else {
        std::snprintf(s, sizeof s, "%.1f %s", rounded, units[u]);
    }
    return s;
}

std::string cache_summary(const CacheSizes &c) {
    std::string s, common;
    bool mixed = false;
    for (const CacheLevel &l : c) {
        if (l.bytes && common.empty()) {
            common = l.source;
        }
        mixed = mixed || (l.bytes && common != l.source);
    }
    for (const CacheLevel &l : c) {
        s += s.empty() ? "" : ", ";
        s += std::string(l.name) + " " + format_bytes((double)l.bytes);
        if (mixed && l.bytes) {
            s += std::string(" (") + l.source + ")";
        }
    }
    if (!mixed && !common.empty()) {
        s += " (" + common + ")";
    }
    return s;
}

} // namespace svbench
