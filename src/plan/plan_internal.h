/*
 * What the planner's files share (src/plan/): building a plan from variant
 * names, installing it, and the built-in plans.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_PLAN_INTERNAL_H
#define SV_PLAN_INTERNAL_H

#include "shadowvol_plan.h"

namespace svplan {

/* NAME is a variant of routine R's table that this CPU runs. */
bool variant_runs_routine(const char *name, sv_routine r);

/* A plan from one variant name per routine; a name this CPU cannot run
 * (or NULL) falls back to the static choice. TICKS may be NULL. */
sv_plan make_plan(int sizeClass, const char *source, const char *const names[SV_NUM_ROUTINES],
                  const double ticks[SV_NUM_ROUTINES]);

/* Makes P the plan of its class unless the class has one of a higher kind
 * (1 built-in < 2 wisdom < 3 measured). */
void install(int sizeClass, const sv_plan &p, int kind);

/* The class's measured plan, when this process measured it. */
bool measured(int sizeClass, sv_plan *out);

/* The built-in plan for this CPU (builtin.cpp). */
sv_plan builtin_plan(int sizeClass);

/* Deform choices (deform_choices.cpp): KIND 2 wisdom, 3 measured (a
 * measurement is never replaced by the wisdom file). As sv_deform_choice_set
 * returns. */
int set_deform_choice(int sizeClass, int r, const char *variant, double ticks, int kind);
/* The class's choice for R when this process measured it. */
bool measured_deform_choice(int sizeClass, int r, sv_deform_choice *out);
void reset_deform_choices();

/* The stencil choice (stencil_choices.cpp), kinds as the deform choices'. */
int set_stencil_choice(const char *method, int tile, double hier_from_area_per_piece, int kind);
bool measured_stencil_choice(sv_stencil_choice *out);
void reset_stencil_choice();

} // namespace svplan

#endif
