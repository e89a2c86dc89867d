/*
 * The deforming-surface choices of include/shadowvol_plan.h (skinning,
 * planes, the one-pass kernel): a name and its ticks per size class and
 * routine, from a measurement in this process or the wisdom file. The
 * planner only keeps them; the animation layer, which owns the kernels,
 * measures them and checks a name against its tables before it runs one.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <array>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "plan_internal.h"

namespace {

struct Slot {
    int kind = 0; /* 0 none, 2 wisdom, 3 measured */
    sv_deform_choice choice{};
};

struct Choices {
    std::mutex lock;
    std::array<std::array<Slot, SV_NUM_DEFORM_ROUTINES>, SV_NUM_SIZE_CLASSES> slot{};
};
Choices &choices() {
    static Choices c;
    return c;
}

bool valid_name(const char *v) {
    if (!v || !*v || std::strlen(v) >= sizeof(sv_deform_choice{}.variant)) return false;
    for (const char *c = v; *c; c++) {
        if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_')) return false;
    }
    return true;
}

bool in_range(int sizeClass, int r) {
    return sizeClass >= 0 && sizeClass < SV_NUM_SIZE_CLASSES && r >= 0 &&
           r < SV_NUM_DEFORM_ROUTINES;
}

} // namespace

namespace svplan {

int set_deform_choice(int sizeClass, int r, const char *variant, double ticks, int kind) {
    if (!in_range(sizeClass, r) || !valid_name(variant) || !(ticks >= 0)) return -1;
    Choices &c = choices();
    std::lock_guard<std::mutex> g(c.lock);
    Slot &s = c.slot[(size_t)sizeClass][(size_t)r];
    if (s.kind > kind) return 0; /* a measurement outranks the wisdom file */
    s.kind = kind;
    std::snprintf(s.choice.variant, sizeof s.choice.variant, "%s", variant);
    s.choice.ticks = ticks;
    s.choice.source = kind == 3 ? "measured" : "wisdom";
    return 0;
}

bool measured_deform_choice(int sizeClass, int r, sv_deform_choice *out) {
    if (!in_range(sizeClass, r)) return false;
    Choices &c = choices();
    std::lock_guard<std::mutex> g(c.lock);
    const Slot &s = c.slot[(size_t)sizeClass][(size_t)r];
    if (s.kind != 3) return false;
    *out = s.choice;
    return true;
}

void reset_deform_choices() {
    Choices &c = choices();
    std::lock_guard<std::mutex> g(c.lock);
    for (auto &cls : c.slot) cls.fill(Slot{});
}

} // namespace svplan

extern "C" {

const char *sv_deform_routine_name(sv_deform_routine r) {
    static const char *const kNames[SV_NUM_DEFORM_ROUTINES] = {"skinning", "derive_planes",
                                                               "skin_planes",
                                                               "derive_planes_clustered"};
    return r >= 0 && r < SV_NUM_DEFORM_ROUTINES ? kNames[r] : nullptr;
}

int sv_deform_choice_for(int sizeClass, sv_deform_routine r, sv_deform_choice *out) {
    if (!in_range(sizeClass, r) || !out) return -1;
    Choices &c = choices();
    std::lock_guard<std::mutex> g(c.lock);
    const Slot &s = c.slot[(size_t)sizeClass][(size_t)r];
    if (s.kind == 0) return 0;
    *out = s.choice;
    return 1;
}

int sv_deform_choice_set(int sizeClass, sv_deform_routine r, const char *variant, double ticks) {
    return svplan::set_deform_choice(sizeClass, r, variant, ticks, 3);
}

} // extern "C"
