/*
 * shadowvol: the project's one command line, with subcommands in the style
 * of git (DESIGN.md section 8). Each subcommand is a function taking its own
 * argv (argv[0] = its name) and returning the exit status; this file only
 * dispatches.
 *
 * Exit status: 0 done; 1 a correctness check failed; 2 bad arguments; 3 a
 * model file could not be loaded (inspect, verify, render, scene, view); 4
 * verify cannot decide; 5 view cannot open a window (no display).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cstdio>
#include <cstring>

#include "bench_cli.h"
#include "accuracy_cli.h"
#include "check_cli.h"
#include "model_cli.h"
#include "render_cli.h"
#include "scene_cli.h"
#include "view_cli.h"
#include "tune_cli.h"

#ifndef SV_PROJECT_VERSION
#define SV_PROJECT_VERSION "unknown"
#endif

namespace {

struct Command {
    const char *name;
    const char *summary;
    int (*run)(int argc, char **argv);
    void (*usage)(FILE *out);
};

const Command kCommands[] = {
    {"bench", "the cycle table of every routine and variant, beside the paper's Pentium 4",
     svbench::bench_main, svbench::bench_usage},
    {"inspect", "what shadow-volume preparation finds in a glTF model, per mesh and in total",
     svcli::inspect_main, svcli::inspect_usage},
    {"verify", "prove a model's shadow volumes closed and right in space, for every variant",
     svcli::verify_main, svcli::verify_usage},
    {"accuracy", "speed against accuracy of the facing decision, per variant, model and light",
     svcli::accuracy_main, svcli::accuracy_usage},
    {"render", "render a scene's shadows in the project's stencil, checked by rays and by Mesa",
     svcli::render_main, svcli::render_usage},
    {"scene",
     "play a glTF scene in time, building only what each frame requires, proved pixel for pixel",
     svcli::scene_main, svcli::scene_usage},
    {"view", "play a scene in a window: orbit, drag a light, switch modes, passes and shortcuts",
     svcli::view_main, svcli::view_usage},
    {"check", "every routine of every variant this CPU runs against c_ref, ABI-checked; --bench",
     svcli::check_main, svcli::check_usage},
    {"tune",
     "measure every variant per routine and mesh size; save this CPU's fastest as its plans",
     svcli::tune_main, svcli::tune_usage},
};

const Command *find_command(const char *name) {
    for (const Command &c : kCommands) {
        if (std::strcmp(c.name, name) == 0) {
            return &c;
        }
    }
    return nullptr;
}

void usage(FILE *out) {
    std::fprintf(out, "usage: shadowvol <command> [options]\n"
                      "       shadowvol help <command>\n"
                      "\n"
                      "CPU shadow-volume construction after J.M.P. van Waveren, \"Shadow Volume\n"
                      "Construction\" (Id Software, 2005).\n"
                      "\n"
                      "commands:\n");
    for (const Command &c : kCommands) {
        std::fprintf(out, "  %-10s %s\n", c.name, c.summary);
    }
    std::fprintf(out,
                 "\n"
                 "'shadowvol <command> --help' describes a command's options.\n"
                 "Exit status: 0 done, 1 a correctness check failed, 2 bad arguments,\n"
                 "3 a model could not be loaded, 4 verify cannot decide (the reason printed),\n"
                 "5 view cannot open a window (no display, or built without SDL2).\n");
}

} // namespace

int main(int argc, char **argv) {
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *first = argv[1];
    if (!std::strcmp(first, "help") || !std::strcmp(first, "--help") || !std::strcmp(first, "-h")) {
        if (argc == 2) {
            usage(stdout);
            return 0;
        }
        const Command *c = find_command(argv[2]);
        if (!c || argc > 3) {
            std::fprintf(stderr, "shadowvol help: %s '%s'\nTry 'shadowvol help'.\n",
                         c ? "unexpected argument" : "unknown command", argv[c ? 3 : 2]);
            return 2;
        }
        c->usage(stdout);
        return 0;
    }
    if (!std::strcmp(first, "--version")) {
        std::printf("shadowvol %s\n", SV_PROJECT_VERSION);
        return 0;
    }
    const Command *c = find_command(first);
    if (!c) {
        std::fprintf(stderr, "shadowvol: unknown command '%s'\nTry 'shadowvol help'.\n", first);
        return 2;
    }
    return c->run(argc - 1, argv + 1);
}
