/*
 * A file a bench run writes its document into (--json FILE, --plot FILE):
 * opened before the measurements, so that a name that cannot be written
 * fails at once rather than after a minute of timing, and removed again
 * when the run ends without a document (a model that did not load, an
 * internal error): a script finds a whole document or none.
 *
 * "-" is standard output.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_OUTPUT_FILE_H
#define SV_BENCH_OUTPUT_FILE_H

#include <cstdio>
#include <stdexcept>
#include <string>

#include <sys/types.h>

namespace svbench {

/* The file cannot be opened: a message naming OPTION, the file and why. */
class OutputFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class OutputFile {
public:
    /* NAME "": nothing is wanted (wanted() is false). OPTION names the
     * option in messages ("--json"). Throws OutputFileError. */
    OutputFile(const std::string &option, const std::string &name);
    ~OutputFile();
    OutputFile(const OutputFile &) = delete;
    OutputFile &operator=(const OutputFile &) = delete;

    bool wanted() const { return f_ != nullptr; }
    bool is_stdout() const { return f_ == stdout; }
    const std::string &name() const { return name_; }

    /* Writes DOC and closes the file. False (with errno) when the document
     * could not be written whole; the file is then removed. */
    bool write(const std::string &doc);

private:
    void discard();
    std::string name_;
    FILE *f_ = nullptr;
    bool regular_ = false; /* what was opened is a regular file */
    dev_t dev_ = 0;
    ino_t ino_ = 0;
};

} // namespace svbench

#endif
