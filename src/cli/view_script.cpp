/*
 * The --script reader of view_script.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "view_script.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "shadowvol_gltf.h"

namespace svcli {
namespace {

long whole_number(const std::string &word, long lo, long hi, const std::string &where,
                  const char *what) {
    errno = 0;
    char *end = nullptr;
    const long v = word.empty() ? 0 : std::strtol(word.c_str(), &end, 10);
    if (word.empty() || *end != 0 || errno == ERANGE || v < lo || v > hi) {
        throw std::runtime_error(where + ": " + what + " needs a whole number from " +
                                 std::to_string(lo) + " to " + std::to_string(hi) + ", not '" +
                                 sv::printable_text(word) + "'");
    }
    return v;
}

} // namespace

std::vector<ScriptEvent> parse_view_script(const std::string &text, const std::string &name) {
    std::vector<ScriptEvent> events;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        number++;
        const std::size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string word; words >> word;) w.push_back(word);
        if (w.empty()) continue;
        const std::string where = sv::printable_text(name) + ":" + std::to_string(number);
        if (w.size() < 2)
            throw std::runtime_error(where + ": expected FRAME EVENT (key, drag, wheel, snap, "
                                             "print, quit)");
        ScriptEvent e;
        e.line = number;
        e.frame = whole_number(w[0], 0, 100000000, where, "FRAME");
        const std::string &kind = w[1];
        const std::size_t args = w.size() - 2;
        auto want = [&](std::size_t n, const char *form) {
            if (args != n) throw std::runtime_error(where + ": expected FRAME " + form);
        };
        if (kind == "key") {
            want(1, "key NAME");
            e.kind = ScriptEvent::key;
            e.text = w[2];
        } else if (kind == "drag") {
            want(5, "drag left|right X0 Y0 X1 Y1");
            e.kind = ScriptEvent::drag;
            if (w[2] != "left" && w[2] != "right")
                throw std::runtime_error(where + ": drag needs left or right, not '" +
                                         sv::printable_text(w[2]) + "'");
            e.button = w[2] == "left" ? 1 : 3;
            e.x0 = (int)whole_number(w[3], 0, 65535, where, "X0");
            e.y0 = (int)whole_number(w[4], 0, 65535, where, "Y0");
            e.x1 = (int)whole_number(w[5], 0, 65535, where, "X1");
            e.y1 = (int)whole_number(w[6], 0, 65535, where, "Y1");
        } else if (kind == "wheel") {
            want(1, "wheel N");
            e.kind = ScriptEvent::wheel;
            e.amount = (int)whole_number(w[2], -1000, 1000, where, "wheel");
        } else if (kind == "snap") {
            want(1, "snap FILE");
            e.kind = ScriptEvent::snap;
            e.text = w[2];
        } else if (kind == "print") {
            want(0, "print");
            e.kind = ScriptEvent::print;
        } else if (kind == "quit") {
            want(0, "quit");
            e.kind = ScriptEvent::quit;
        } else {
            throw std::runtime_error(where + ": unknown event '" + sv::printable_text(kind) +
                                     "' (key, drag, wheel, snap, print, quit)");
        }
        events.push_back(e);
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const ScriptEvent &a, const ScriptEvent &b) { return a.frame < b.frame; });
    return events;
}

std::vector<ScriptEvent> read_view_script(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("--script " + sv::printable_text(path) + ": cannot read it");
    std::ostringstream text;
    text << f.rdbuf();
    return parse_view_script(text.str(), path);
}

} // namespace svcli
