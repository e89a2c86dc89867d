/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "json_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace svbench {

namespace {

/* The length of the well-formed UTF-8 sequence at S[I] (RFC 3629: no
 * overlong forms, no surrogates, nothing above U+10FFFF), or 0. */
size_t utf8_sequence(const std::string &s, size_t i) {
    const auto byte = [&](size_t k) { return (unsigned char)s[k]; };
    const unsigned char c = byte(i);
    size_t n;
    unsigned char lo = 0x80, hi = 0xbf; /* range of the second byte */
    if (c >= 0xc2 && c <= 0xdf) {
        n = 2;
    } else if (c >= 0xe0 && c <= 0xef) {
        n = 3;
        lo = c == 0xe0 ? 0xa0 : 0x80;
        hi = c == 0xed ? 0x9f : 0xbf;
    } else if (c >= 0xf0 && c <= 0xf4) {
        n = 4;
        lo = c == 0xf0 ? 0x90 : 0x80;
        hi = c == 0xf4 ? 0x8f : 0xbf;
    } else {
        return 0;
    }
    if (i + n > s.size() || byte(i + 1) < lo || byte(i + 1) > hi) {
        return 0;
    }
    for (size_t k = 2; k < n; k++) {
        if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) {
            return 0;
        }
    }
    return n;
}

} // namespace

std::string json_quote(const std::string &s) {
    std::string out = "\"";
    for (size_t i = 0; i < s.size();) {
        const unsigned char c = (unsigned char)s[i];
        if (c == '"' || c == '\\') {
            out += '\\';
            out += (char)c;
            i++;
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
            i++;
        } else if (c < 0x80) {
            out += (char)c;
            i++;
        } else if (const size_t n = utf8_sequence(s, i)) {
            out.append(s, i, n);
            i += n;
        } else {
            out += "\\ufffd";
            i++;
        }
    }
    return out + "\"";
}

namespace {

template <class F> std::string shortest(F v) {
    if (!std::isfinite(v)) {
        throw std::logic_error("JSON has no number for a NaN or an infinity");
    }
    char buf[48];
    const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
    if (r.ec != std::errc()) {
        throw std::logic_error("cannot format a number for JSON");
    }
    return std::string(buf, r.ptr);
}

} // namespace

std::string json_number(double v) { return shortest(v); }

std::string json_number(float v) { return shortest(v); }

void JsonWriter::member_break() {
    Level &l = stack_.back();
    if (!l.empty) {
        out_ += ',';
    }
    if (!l.inline_) {
        out_ += '\n';
        out_.append(2 * stack_.size(), ' ');
    } else if (!l.empty) {
        out_ += ' ';
    }
    l.empty = false;
}

void JsonWriter::key(const std::string &k) {
    if (stack_.empty() || stack_.back().close != '}' || afterKey_) {
        throw std::logic_error("JSON: a key outside an object");
    }
    member_break();
    out_ += json_quote(k) + ": ";
    afterKey_ = true;
}

void JsonWriter::before_value() {
    if (afterKey_) {
        afterKey_ = false;
    } else if (stack_.empty()) {
        if (!out_.empty()) {
            throw std::logic_error("JSON: a second document");
        }
    } else if (stack_.back().close == '}') {
        throw std::logic_error("JSON: a value without a key in an object");
    } else {
        member_break();
    }
}

void JsonWriter::open(char c, bool inline_) {
    const bool outerInline = !stack_.empty() && stack_.back().inline_;
    before_value();
    out_ += c;
    stack_.push_back(Level{c == '{' ? '}' : ']', inline_ || outerInline});
}

void JsonWriter::close(char c) {
    if (stack_.empty() || stack_.back().close != c || afterKey_) {
        throw std::logic_error("JSON: unbalanced containers");
    }
    const Level l = stack_.back();
    stack_.pop_back();
    if (!l.inline_ && !l.empty) {
        out_ += '\n';
        out_.append(2 * stack_.size(), ' ');
    }
    out_ += c;
    if (stack_.empty()) {
        out_ += '\n';
    }
}

void JsonWriter::scalar(const std::string &text) {
    before_value();
    out_ += text;
}

const std::string &JsonWriter::str() const {
    if (!stack_.empty()) {
        throw std::logic_error("JSON: a container is still open");
    }
    return out_;
}

} // namespace svbench
