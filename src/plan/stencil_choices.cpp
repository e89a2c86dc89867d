/*
 * The stencil pass's method of include/shadowvol_plan.h: a method name,
 * hier's tile side and auto's threshold, from a measurement in this
 * process (`shadowvol tune`) or the wisdom file. The planner only keeps
 * them; the renderer, which owns the methods, reads them as its default
 * (src/cli/stencil_default.cpp).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cstdio>
#include <cstring>
#include <mutex>

#include "plan_internal.h"

namespace {

struct Slot {
    std::mutex lock;
    int kind = 0; /* 0 none, 2 wisdom, 3 measured */
    sv_stencil_choice choice{};
};
Slot &slot() {
    static Slot s;
    return s;
}

bool valid_method(const char *m) {
    if (!m) return false;
    for (const char *name : {"bf", "db", "hier", "auto"}) {
        if (std::strcmp(m, name) == 0) return true;
    }
    return false;
}

} // namespace

namespace svplan {

int set_stencil_choice(const char *method, int tile, double hier_from_area_per_piece, int kind) {
    if (!valid_method(method) || !(tile == 4 || tile == 8 || tile == 16 || tile == 32) ||
        !(hier_from_area_per_piece >= 0)) { /* NaN fails too */
        return -1;
    }
    Slot &s = slot();
    std::lock_guard<std::mutex> g(s.lock);
    if (s.kind > kind) return 0; /* a measurement outranks the wisdom file */
    s.kind = kind;
    std::snprintf(s.choice.method, sizeof s.choice.method, "%s", method);
    s.choice.tile = tile;
    s.choice.hier_from_area_per_piece = hier_from_area_per_piece;
    s.choice.source = kind == 3 ? "measured" : "wisdom";
    return 0;
}

bool measured_stencil_choice(sv_stencil_choice *out) {
    Slot &s = slot();
    std::lock_guard<std::mutex> g(s.lock);
    if (s.kind != 3) return false;
    *out = s.choice;
    return true;
}

void reset_stencil_choice() {
    Slot &s = slot();
    std::lock_guard<std::mutex> g(s.lock);
    s.kind = 0;
    s.choice = sv_stencil_choice{};
}

} // namespace svplan

extern "C" {

int sv_stencil_choice_for(sv_stencil_choice *out) {
    if (!out) return -1;
    Slot &s = slot();
    std::lock_guard<std::mutex> g(s.lock);
    if (s.kind == 0) return 0;
    *out = s.choice;
    return 1;
}

int sv_stencil_choice_set(const char *method, int tile, double hier_from_area_per_piece) {
    return svplan::set_stencil_choice(method, tile, hier_from_area_per_piece, 3);
}

} // extern "C"
