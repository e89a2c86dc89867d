/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "output_file.h"

#include <cerrno>
#include <cstring>

#include <sys/stat.h>
#include <unistd.h>

namespace svbench {

OutputFile::OutputFile(const std::string &option, const std::string &name) : name_(name) {
    if (name.empty()) {
        return;
    }
    f_ = name == "-" ? stdout : std::fopen(name.c_str(), "w");
    if (!f_) {
        throw OutputFileError(option + ": cannot write " + name + ": " + std::strerror(errno));
    }
    struct stat st;
    if (f_ != stdout && fstat(fileno(f_), &st) == 0 && S_ISREG(st.st_mode)) {
        regular_ = true;
        dev_ = st.st_dev;
        ino_ = st.st_ino;
    }
}

OutputFile::~OutputFile() {
    if (f_ && f_ != stdout) {
        std::fclose(f_);
        discard();
    }
}

bool OutputFile::write(const std::string &doc) {
    const bool ok = std::fwrite(doc.data(), 1, doc.size(), f_) == doc.size() &&
                    std::fflush(f_) == 0;
    if (f_ != stdout) {
        const bool closed = std::fclose(f_) == 0;
        f_ = nullptr;
        if (!(ok && closed)) {
            const int e = errno;
            discard(); /* no half document */
            errno = e;
        }
        return ok && closed;
    }
    return ok;
}

/* Removes the file, when NAME is that very regular file: never a device, a
 * pipe, or a link such as /dev/stdout, whose name would be removed rather
 * than what it points to. */
void OutputFile::discard() {
    struct stat st;
    if (regular_ && lstat(name_.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_dev == dev_ &&
        st.st_ino == ino_) {
        std::remove(name_.c_str());
    }
}

} // namespace svbench
