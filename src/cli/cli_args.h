/*
 * Option parsing shared by the model subcommands (inspect, verify):
 * "--opt value" and "--opt=value", whole numbers with ranges, usage errors
 * as exceptions that the subcommand turns into exit status 2.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_CLI_ARGS_H
#define SV_CLI_CLI_ARGS_H

#include <cerrno>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "shadowvol_gltf.h"

namespace svcli {

struct UsageError {
    std::string message;
};

/* TEXT from the command line as a message may quote it: at most
 * sv::kGltfMaxQuotedBytes, printable UTF-8 (sv::printable_text). */
inline std::string quoted(const std::string &text) { return sv::printable_text(text); }

[[noreturn]] inline void usage_error(const std::string &message) { throw UsageError{message}; }

/* Walks argv[1..]: next() gives the next argument split at '=' for long
 * options; value() takes the option's value (inline or the next argument). */
class ArgReader {
public:
    ArgReader(int argc, char **argv) : argc_(argc), argv_(argv) {}
    bool next() {
        if (++i_ >= argc_) return false;
        arg_ = argv_[i_];
        opt_ = arg_;
        inline_ = false;
        const std::size_t eq = arg_.find('=');
        if (arg_.rfind("--", 0) == 0 && eq != std::string::npos) {
            opt_ = arg_.substr(0, eq);
            value_ = arg_.substr(eq + 1);
            inline_ = true;
        }
        return true;
    }
    const std::string &arg() const { return arg_; }
    const std::string &opt() const { return opt_; }
    bool is(const char *name) const { return opt_ == name; }
    bool is_flag(const char *name) const {
        if (opt_ != name) return false;
        if (inline_) usage_error(opt_ + " takes no value");
        return true;
    }
    std::string value() {
        if (inline_) return value_;
        if (i_ + 1 >= argc_) usage_error(opt_ + " needs a value");
        return argv_[++i_];
    }
    long long integer(long long lo, long long hi) {
        const std::string s = value();
        errno = 0;
        char *end = nullptr;
        const bool digits = !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
        const long long v = digits ? std::strtoll(s.c_str(), &end, 10) : 0;
        if (!digits || errno == ERANGE || *end || v < lo || v > hi) {
            usage_error(opt_ + " needs a whole number from " + std::to_string(lo) + " to " +
                        std::to_string(hi) + ", not '" + quoted(s) + "'");
        }
        return v;
    }
    uint64_t seed() {
        const std::string s = value();
        errno = 0;
        char *end = nullptr;
        const bool digits = !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
        const unsigned long long v = digits ? std::strtoull(s.c_str(), &end, 10) : 0;
        if (!digits || errno == ERANGE || *end) {
            usage_error(opt_ + " needs a whole number from 0 to 18446744073709551615, not '" +
                        quoted(s) + "'");
        }
        return v;
    }

private:
    int argc_;
    char **argv_;
    int i_ = 0;
    std::string arg_, opt_, value_;
    bool inline_ = false;
};

/* A JSON string literal (quotes included). */
inline std::string json_string(const std::string &s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += (char)c;
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += (char)c;
        }
    }
    return out + "\"";
}

} // namespace svcli

#endif
