/*
 * shadowvol: dispatch by measurement (issue 15). sv_best_variant() picks the
 * highest instruction set the CPU runs; that is not always the fastest
 * (on an Intel Sapphire Rapids the AVX2 volume kernels beat the AVX-512
 * ones from about 100k triangles on; on AMD before Zen 3, BMI2's pdep and
 * AVX2's gathers are microcoded). A plan is one variant per routine for
 * one size class of mesh, chosen by timing every variant this CPU runs on
 * a generated mesh of that class (FFTW's "wisdom" is the model):
 *
 *   const sv_plan *p = sv_plan_for(numTriangles, SV_PLAN_ESTIMATE);
 *   p->calculate_facing(planes, numTriangles, &light, facing);
 *   n = sv_create_shadow_volume(&p->kernels, out, ...);
 *
 * Where a plan comes from, in order:
 *   1. measured in this process (sv_plan_measure, SV_PLAN_MEASURE);
 *   2. the wisdom file (sv_wisdom_load; `shadowvol tune` writes it), for
 *      the CPU model it was measured on only;
 *   3. built-in: the static choice (sv_best_variant and
 *      sv_best_facing_variant), with the exceptions measured on CPUs this
 *      project has run on (src/plan/builtin.cpp names them and their
 *      source).
 * SV_PLAN_MEASURE measures a class on its first use when neither 1 nor 2
 * has it (tens of milliseconds for the small classes, half a second for
 * class 2 and a few seconds for the largest, most of it building and
 * lighting its million-triangle mesh); SV_PLAN_ESTIMATE never measures.
 *
 * Every plan's kernels are those of the variant table, so a plan computes
 * exactly what c_ref computes; its kernels' alignment needs are the largest
 * of the chosen variants' (kernels.align_*). Thread-safe.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_PLAN_H
#define SHADOWVOL_PLAN_H

#include <stddef.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The routines a plan chooses for, in pipeline order. */
typedef enum sv_routine {
    SV_ROUTINE_CALCULATE_FACING,     /* appendix A */
    SV_ROUTINE_CALCULATE_CULL_BITS,  /* appendix B */
    SV_ROUTINE_COUNT_FACING,         /* C */
    SV_ROUTINE_COUNT_FACING_CULL,    /* D */
    SV_ROUTINE_CREATE_SIL_TRIANGLES, /* E */
    SV_ROUTINE_CREATE_CAP_TRIANGLES, /* F */
    SV_NUM_ROUTINES
} sv_routine;
/* "calculate_facing", ... (the benchmark's names); NULL out of range. */
const char *sv_routine_name(sv_routine r);

/* The static choice for routine R: the name of the variant
 * sv_best_facing_variant() (A, B) or sv_best_variant() (C-F) gives; NULL out
 * of range. A measured plan keeps it unless another variant is more than 3%
 * faster. */
const char *sv_static_variant_name(sv_routine r);

/* Size classes by triangle count: 0 below 4096 (the arrays fit L1/L2),
 * 1 below 65536, 2 below 524288, 3 from there on (DRAM). */
#define SV_NUM_SIZE_CLASSES 4
int sv_size_class(int numTriangles);
/* The triangle count of the mesh a class is measured on. */
int sv_size_class_triangles(int sizeClass);

typedef struct sv_plan {
    int size_class;
    const char *source;                   /* "measured", "wisdom" or "built-in" */
    const char *variant[SV_NUM_ROUTINES]; /* the chosen variant's name per routine */
    /* Median TSC ticks per call of each routine's choice on the class's
     * mesh, where measured (0 for built-in plans). */
    double ticks[SV_NUM_ROUTINES];
    sv_calculate_facing_fn calculate_facing;
    sv_calculate_cull_bits_fn calculate_cull_bits;
    /* C-F as one variant (name "planned"), for sv_create_shadow_volume and
     * the *_checked entry points. */
    sv_variant kernels;
    /* The same variant's CalculateFacing fused with the count
     * (sv_calculate_facing_count_fn): what sv_shadow_volume_for_light
     * calls instead of calculate_facing + kernels.count_facing. Last, so
     * that the fields before it keep the offsets they had before it
     * existed. */
    sv_calculate_facing_count_fn calculate_facing_count;
} sv_plan;

enum { SV_PLAN_ESTIMATE = 0, SV_PLAN_MEASURE = 1 };

/* The plan for a mesh of NUMTRIANGLES triangles (its size class). Never
 * NULL. */
const sv_plan *sv_plan_for(int numTriangles, unsigned flags);

/* One variant's time in a measurement. */
typedef struct sv_plan_timing {
    int size_class;
    sv_routine routine;
    const char *variant;
    double ticks; /* TSC ticks per call: the lowest of the rounds' medians */
} sv_plan_timing;

/* Measures size class SIZECLASS now (every variant this CPU runs, every
 * routine, moving lights, each call checked against c_ref) and makes the
 * winners this process's plan for the class. The variants are timed in
 * rounds, a block of calls of each per round, and a routine keeps its
 * static choice unless another variant is more than 3% faster both
 * overall and in 4 of every 5 rounds against the static choice's time in
 * the same round (closer or less steady timings are noise: a shared
 * machine has slow phases). When TIMINGS is not NULL, up
 * to MAXTIMINGS entries are written there. Returns the number of timings
 * taken (which may exceed MAXTIMINGS), or -1 when SIZECLASS is out of
 * range or a variant disagreed with c_ref (a bug: nothing is planned). */
int sv_plan_measure(int sizeClass, sv_plan_timing *timings, int maxTimings);

/* This CPU, as the wisdom file keys it: vendor, family, model, stepping,
 * the ISA level, and the brand string ("AuthenticAMD 23/1/2 avx2 AMD
 * EPYC"). Returns BUF. */
const char *sv_cpu_model_key(char *buf, size_t size);

/* The wisdom file: $SV_WISDOM when set, else $XDG_CACHE_HOME/shadowvol/
 * wisdom, else $HOME/.cache/shadowvol/wisdom. Returns BUF ("" when none
 * can be formed). */
const char *sv_wisdom_default_path(char *buf, size_t size);
/* Writes the measured plans of this process to PATH (creating the folder),
 * keeping the other CPUs' sections a file already holds. 0 or -1. */
int sv_wisdom_save(const char *path);
/* Reads PATH; plans measured on THIS CPU model become the "wisdom" plans
 * (classes measured in this process keep theirs). Returns the number of
 * classes read for this CPU (0 when the file has none), or -1 when PATH
 * cannot be read or is malformed (nothing is taken from it then). */
int sv_wisdom_load(const char *path);

/* ---- One call per light ------------------------------------------------
 * A surface prepared for shadow volumes (what sv_prepare_* or the caller's
 * own code made): the arrays every light's volume reads. */
typedef struct sv_surface {
    const Plane *planes;     /* numIndices / 3 triangle planes (appendix A) */
    const int *indices;      /* numIndices vertex numbers, 3 per triangle */
    int numIndices;          /* a multiple of 3, >= 0 */
    const SilEdge *silEdges; /* numSilEdges edges */
    int numSilEdges;
    const Vec4 *positions; /* numVerts vertices; read only with light planes */
    int numVerts;
    Bounds bounds; /* contains every position (appendix B's box test) */
} sv_surface;

/* As sv_plan_measure, on the caller's own SURFACE rather than the
 * generated character: the plan of the size class of its triangle count,
 * measured on it (its own shape, facing and silhouette ratios), lit by 8
 * point lights on a ring around its bounds. Its arrays are copied first
 * (no alignment is asked of them; surface->bounds is not read, the
 * positions' own box is used). Returns the timings taken, -1 when a
 * variant disagreed with c_ref, or -2 when SURFACE breaks a contract of
 * sv_shadow_volume_for_light (NULL arrays, fewer than one triangle or a
 * count not a multiple of 3, an index, SilEdge or vertex out of range, an
 * odd SilEdge vertex, counts whose volume overflows an int) or has a
 * plane or position that is not finite: nothing is planned then. */
int sv_plan_measure_surface(const sv_surface *surface, sv_plan_timing *timings, int maxTimings);

/* The shadow volume of SURFACE for LIGHT in one call: CalculateFacing and
 * the count fused (no second pass over the facing bytes), then, with
 * LIGHTPLANES (the light volume's SV_NUM_LIGHT_PLANES planes; NULL: no
 * light volume), CalculateCullBits and its decision: a surface inside the
 * light volume takes the path without culling, any other goes through
 * CountFacingCull; then the silhouette quads and the caps, into
 * SHADOWINDICES. Every kernel is PLAN's (NULL: sv_plan_for(numTriangles,
 * SV_PLAN_ESTIMATE)); a kernel whose alignment need a buffer does not meet
 * is replaced, for that call, by the same routine of the highest entry of
 * the variant table (sv_variants: reference first, widest ISA last) that
 * this CPU runs and whose alignment needs all the buffers meet. The indices written and the count
 * returned are exactly those of sv_create_shadow_volume with the reference
 * kernels (c_ref) after the reference's A and B.
 *   shadowIndices  capacity ints, capacity >= sv_shadow_volume_capacity(
 *                  numIndices, numSilEdges) (SV_E_CAPACITY otherwise); the
 *                  ints past the returned count are scratch.
 *   facing         numIndices / 3 + 1 bytes of scratch; on return the
 *                  facing bytes (1 for culled triangles, with light planes
 *                  and a surface not wholly inside the light volume).
 *   cullBits       numVerts bytes of scratch; needed (non-NULL) only with
 *                  LIGHTPLANES.
 * Returns the number of indices (0: the surface casts no shadow), or a
 * negative SV_E_* code for NULL pointers, bad counts, output room below
 * the bound, or a count whose output does not fit in an int (nothing is
 * then written). The contents (vertex numbers, SilEdges) are trusted as
 * sv_create_shadow_volume trusts them: sv_create_shadow_volume_checked
 * validates them. Thread-safe (the plan is immutable). */
int sv_shadow_volume_for_light(const sv_plan *plan, const sv_surface *surface, const Vec4 *light,
                               const Plane *lightPlanes, int *shadowIndices, size_t capacity,
                               uint8_t *facing, uint8_t *cullBits);

/* ---- Deforming surfaces: skinning and per-frame planes -----------------
 * What a skinned surface runs each frame before any light: a skinning
 * kernel (sv::skinning_kernels), a planes variant (sv_planes_variants) and,
 * where it is faster than the two in a row, a one-pass kernel that does
 * both (sv::skin_planes_kernels). Those tables live in the animation
 * layer, which measures them (sv::measure_deform_plan, `shadowvol tune`)
 * and asks here for the choice: per size class, measured in this process
 * or read from the wisdom file (this CPU model's section, lines
 * "class N skinning avx2 2.9", ticks per triangle). With neither, the
 * animation layer uses its static choice (sv::deform_plan_for says which). */
typedef enum sv_deform_routine {
    SV_DEFORM_SKINNING,         /* a skinning kernel's name */
    SV_DEFORM_DERIVE_PLANES,    /* a planes variant's name */
    SV_DEFORM_SKIN_PLANES,      /* a one-pass kernel's name, or "none": two passes */
    SV_DEFORM_PLANES_CLUSTERED, /* a clustered planes kernel's name (sv_planes_clustered_variants),
                                   or "none": the planes variant */
    SV_NUM_DEFORM_ROUTINES
} sv_deform_routine;
/* "skinning", "derive_planes", "skin_planes", "derive_planes_clustered";
 * NULL out of range. */
const char *sv_deform_routine_name(sv_deform_routine r);

typedef struct sv_deform_choice {
    char variant[32];   /* the chosen name */
    double ticks;       /* ticks per triangle where it was measured */
    const char *source; /* "measured" or "wisdom" */
} sv_deform_choice;
/* Fills OUT with the choice for R in SIZECLASS and returns 1; 0 when there
 * is none (nothing measured, nothing in the wisdom file), -1 out of range. */
int sv_deform_choice_for(int sizeClass, sv_deform_routine r, sv_deform_choice *out);
/* Records a measurement's choice for this process (sv_wisdom_save writes
 * it; the wisdom file never overrides it). VARIANT: up to 31 characters of
 * [a-z0-9_]. 0, or -1 for a bad class, routine or name. */
int sv_deform_choice_set(int sizeClass, sv_deform_routine r, const char *variant, double ticks);

/* ---- The stencil pass's method ----------------------------------------
 * What `shadowvol render`, `scene` and `view` draw the stencil with when
 * no --stencil is given: a method ("bf", "db", "hier" or "auto"), hier's
 * tile side (4, 8, 16, 32), and auto's threshold (a light goes to hier
 * when its volume pieces' mean area is at least that many pixels;
 * infinity: every light bf). Measured by `shadowvol tune` (bench
 * --stencil-rule's fit, docs/RENDERING.md) or read from the wisdom file
 * (this CPU model's section, a line "stencil auto 32 65.0"). With
 * neither, the renderer's own default: auto with the threshold measured
 * offline (kDefaultHierFromAreaPerPiece). Every method gives the same
 * bytes. */
typedef struct sv_stencil_choice {
    char method[8];                  /* "bf", "db", "hier" or "auto" */
    int tile;                        /* hier's tile side */
    double hier_from_area_per_piece; /* auto's threshold, pixels (may be infinity) */
    const char *source;              /* "measured" or "wisdom" */
} sv_stencil_choice;
/* Fills OUT and returns 1; 0 when there is none; -1 for OUT NULL. */
int sv_stencil_choice_for(sv_stencil_choice *out);
/* Records a measurement's choice for this process (sv_wisdom_save writes
 * it; the wisdom file never overrides it). 0, or -1 for a method, tile or
 * threshold (NaN, negative) that is not one. */
int sv_stencil_choice_set(const char *method, int tile, double hier_from_area_per_piece);

/* Forgets every measured and wisdom plan, deform choice and stencil
 * choice (tests). */
void sv_plan_reset(void);

#ifdef __cplusplus
}
#endif

#endif
