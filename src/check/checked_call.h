// checked_call(gen, fn, args...): calls fn through the ABI checker with
// argument words built from fn's own prototype, so no caller can forget
// one: every 32-bit integer parameter gets random garbage in bits 32-63
// (the x86-64 ABIs leave them undefined; a routine that reads rsi where it
// should read esi then computes garbage), pointers and 64-bit integers
// travel unchanged, and the unused argument words are garbage too.
// GEN is any generator with uint64_t next().
//
//   uint32_t failed;
//   int n = svcheck::checked_call<decltype(&sv_count_facing_avx2)>(
//       rng, &failed, sv_count_facing_avx2, facing, count);
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>

#include "abi_check.h"

namespace svcheck {

template <class F> struct fn_traits;
template <class R, class... P> struct fn_traits<R (*)(P...)> {
    using ret = R;
    using params = std::tuple<P...>;
    static constexpr size_t arity = sizeof...(P);
};

template <class Fn>
constexpr bool is_fn_ptr_v = std::is_pointer_v<Fn> &&std::is_function_v<std::remove_pointer_t<Fn>>;

// The register word for one argument of type T.
template <class T> uintptr_t arg_word(T v, uint64_t garbage) {
    if constexpr (std::is_pointer_v<T> || std::is_null_pointer_v<T>) {
        return (uintptr_t)v;
    } else {
        static_assert(std::is_integral_v<T> || std::is_enum_v<T>,
                      "checked_call passes integers and pointers only");
        static_assert(sizeof(T) <= sizeof(uintptr_t), "argument wider than a register");
        if constexpr (sizeof(T) == 4 && sizeof(uintptr_t) == 8) {
            // Neither the zero nor the sign extension: a routine relying on
            // either is caught.
            uint32_t hi = (uint32_t)(garbage >> 32);
            if (hi == 0 || hi == 0xFFFFFFFFu) hi ^= 0xDEADBEEFu;
            return (uintptr_t)(((uint64_t)hi << 32) | (uint32_t)v);
        } else {
            return (uintptr_t)v;
        }
    }
}

// Fresh callee-saved canaries, stack canaries and xmm garbage.
template <class Gen> void scramble(Gen &gen) {
    for (auto &c : sv_abi_canary) c = (uintptr_t)gen.next();
    for (auto &c : sv_abi_stack_canary) c = (uintptr_t)gen.next();
    for (size_t i = 0; i < sizeof sv_abi_xmm_garbage; i += 8) {
        uint64_t w = gen.next();
        for (int b = 0; b < 8; b++) sv_abi_xmm_garbage[i + b] = (uint8_t)(w >> (8 * b));
    }
}

inline void detect_once() {
    static const uint32_t flags = sv_abi_detect();
    (void)flags;
}

template <class Fn, class Gen, class... A, size_t... I>
void fill_words(uintptr_t *w, Gen &gen, std::index_sequence<I...>, A... args) {
    using P = typename fn_traits<Fn>::params;
    ((w[I] = arg_word<std::tuple_element_t<I, P>>(static_cast<std::tuple_element_t<I, P>>(args),
                                                  gen.next())),
     ...);
}

// Calls fn(args...) checked; *failed receives sv_abi_failed (0: all kept).
template <class Fn, class Gen, class... A, class = std::enable_if_t<is_fn_ptr_v<Fn>>>
typename fn_traits<Fn>::ret checked_call(Gen &gen, uint32_t *failed, Fn fn, A... args) {
    using R = typename fn_traits<Fn>::ret;
    static_assert(sizeof...(A) == fn_traits<Fn>::arity, "wrong number of arguments");
    static_assert(sizeof...(A) <= SV_ABI_ARGS, "the checker passes 8 argument words");
    // (sizeof of a char stands in for void's: sizeof(void) is a GNU extension
    // that warns, and || does not keep the compiler from evaluating it.)
    static_assert(sizeof(std::conditional_t<std::is_void_v<R>, char, R>) <= sizeof(uintptr_t),
                  "return value wider than a register");
    detect_once();
    uintptr_t words[SV_ABI_ARGS];
    for (auto &w : words) w = (uintptr_t)gen.next();
    fill_words<Fn>(words, gen, std::index_sequence_for<A...>{}, args...);
    scramble(gen);
    sv_abi_failed = 0;
    const uintptr_t r = sv_abi_checked_call((const void *)fn, words);
    *failed = sv_abi_failed;
    if constexpr (std::is_void_v<R>) {
        (void)r;
    } else if constexpr (std::is_pointer_v<R>) {
        return (R)r;
    } else {
        // Only the low sizeof(R) bytes of rax are defined.
        using U = std::make_unsigned_t<R>;
        return (R)(U)r;
    }
}

} // namespace svcheck
