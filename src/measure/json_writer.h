/*
 * A small streaming JSON writer for the bench's --json document: strings
 * escaped (quote, backslash, control characters; invalid UTF-8 replaced by
 * U+FFFD, so any file name gives valid JSON), numbers in the shortest form
 * that reads back to the same double, and only finite ones (a NaN or an
 * infinity is a bug in the caller: std::logic_error).
 *
 * Layout: every container on its own lines, indented by two spaces, except
 * those opened with `inline_` = true, which stay on one line (one line per
 * result row, for grep and diff).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_JSON_WRITER_H
#define SV_BENCH_JSON_WRITER_H

#include <cstdint>
#include <string>
#include <vector>

namespace svbench {

/* S as a JSON string literal, quotes included. */
std::string json_quote(const std::string &s);
/* V in the shortest form that reads back as V; throws std::logic_error
 * when V is not finite. */
std::string json_number(double v);
/* The same for a float: the shortest form that reads back as that float
 * (1.9376148, not 1.9376147985458374). */
std::string json_number(float v);

class JsonWriter {
public:
    void begin_object(bool inline_ = false) { open('{', inline_); }
    void end_object() { close('}'); }
    void begin_array(bool inline_ = false) { open('[', inline_); }
    void end_array() { close(']'); }
    /* The next value's name (inside an object). */
    void key(const std::string &k);

    void value(const std::string &s) { scalar(json_quote(s)); }
    void value(const char *s) { scalar(json_quote(s)); }
    void value(bool b) { scalar(b ? "true" : "false"); }
    void value(int v) { scalar(std::to_string(v)); }
    void value(long v) { scalar(std::to_string(v)); }
    void value(long long v) { scalar(std::to_string(v)); }
    void value(unsigned long long v) { scalar(std::to_string(v)); }
    void value(double v) { scalar(json_number(v)); }
    void value(float v) { scalar(json_number(v)); }
    void null() { scalar("null"); }

    /* The document; throws std::logic_error while a container is open. */
    const std::string &str() const;

private:
    struct Level {
        char close;
        bool inline_;
        bool empty = true;
    };
    void member_break(); /* the comma and line break before a member */
    void before_value();
    void open(char c, bool inline_);
    void close(char c);
    void scalar(const std::string &text);

    std::string out_;
    std::vector<Level> stack_;
    bool afterKey_ = false;
};

} // namespace svbench

#endif
