/*
 * The stencil pass of stencil_pass.h: the methods by name, and the one
 * each frame runs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "stencil_pass.h"

#include <string>

namespace sv::render {
namespace {

struct MethodName {
    StencilMethod method;
    const char *name;
};
constexpr MethodName kMethods[] = {
    {StencilMethod::brute_force, "bf"},
    {StencilMethod::depth_bounds, "db"},
    {StencilMethod::hierarchical, "hier"},
};

} // namespace

const char *stencil_method_name(StencilMethod m) {
    for (const MethodName &k : kMethods) {
        if (k.method == m) return k.name;
    }
    return "?";
}

bool stencil_method_by_name(const std::string &name, StencilMethod &method) {
    for (const MethodName &k : kMethods) {
        if (name == k.name) {
            method = k.method;
            return true;
        }
    }
    return false;
}

std::string stencil_method_names() {
    std::string s;
    for (const MethodName &k : kMethods) s += (s.empty() ? "" : ", ") + std::string(k.name);
    return s;
}

bool valid_stencil_tile(int side) { return side == 4 || side == 8 || side == 16 || side == 32; }

StencilPassResult stencil_pass(StencilMethod method, const StencilPassInputs &in) {
    switch (method) {
    case StencilMethod::brute_force: return stencil_pass_brute_force(in);
    case StencilMethod::depth_bounds: return stencil_pass_depth_bounds(in);
    case StencilMethod::hierarchical: return stencil_pass_hierarchical(in);
    }
    return stencil_pass_brute_force(in); /* (every method is a case above) */
}

} // namespace sv::render
