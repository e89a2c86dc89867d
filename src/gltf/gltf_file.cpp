/*
 * The glTF loader's file level: the whole file read, the GLB container's
 * layout checked, the JSON's nesting bounded (issue 17) before tinygltf
 * parses it, tinygltf's warnings kept as notes and its errors (and
 * exceptions) turned into GltfError. Every failure of the loader goes
 * through fail_file: "<path>: <problem>", bounded and printable.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gltf_detail.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace sv {
namespace gltf_detail {

namespace {

/* tinygltf insists on decoding images; shadow volumes need none. */
bool ignore_image(tinygltf::Image *, const int, std::string *, std::string *, int, int,
                  const unsigned char *, int, void *) {
    return true;
}

/* A whole message's bound: a few quoted texts and the words around them. */
constexpr std::size_t kMaxMessageBytes = 4 * kGltfMaxQuotedBytes;

/* The deepest nesting of arrays and objects in JSON text, stopping at the
 * first byte that goes past LIMIT (*at gets its offset); strings (with
 * their escapes) skipped. Malformed text is tinygltf's to report. */
int json_depth(const unsigned char *p, std::size_t n, int limit, std::size_t *at) {
    int depth = 0, deepest = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < n; i++) {
        const unsigned char c = p[i];
        if (in_string) {
            if (c == '\\') {
                i++;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > deepest) {
                deepest = depth;
                if (deepest > limit) {
                    *at = i;
                    return deepest;
                }
            }
        } else if (c == ']' || c == '}') {
            depth--;
        }
    }
    return deepest;
}

void check_json_depth(const std::string &path, const unsigned char *p, std::size_t n,
                      std::size_t offset, const char *where) {
    std::size_t at = 0;
    if (json_depth(p, n, kGltfMaxJsonDepth, &at) > kGltfMaxJsonDepth) {
        fail_file(path, std::string(where) + " nests arrays and objects more than " +
                            std::to_string(kGltfMaxJsonDepth) + " deep (at byte " +
                            std::to_string(offset + at) +
                            "); refused before parsing (glTF needs about 8 levels)");
    }
}

bool has_glb_magic(const std::vector<unsigned char> &bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

uint32_t read_u32le(const unsigned char *p) {
    uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

/* Checks the GLB container: 12-byte header (magic, version 2, length),
 * then chunks of (length, type, body) that all end within the declared
 * length, the first one JSON. Returns the declared length: the bytes that
 * go to tinygltf. Bytes past it are ignored with a note. */
uint32_t check_glb_layout(const std::string &path, const std::vector<unsigned char> &bytes,
                          std::vector<std::string> &notes) {
    const std::size_t size = bytes.size();
    if (size < 12) {
        fail_file(path,
                  "truncated GLB: the header needs 12 bytes, the file has " + std::to_string(size));
    }
    const uint32_t version = read_u32le(bytes.data() + 4);
    const uint32_t length = read_u32le(bytes.data() + 8);
    if (version != 2) {
        fail_file(path, "GLB version " + std::to_string(version) + " is not supported (only 2)");
    }
    if (length > size) {
        fail_file(path, "truncated GLB: the header declares " + std::to_string(length) +
                            " bytes, the file has " + std::to_string(size));
    }
    if (length < 20) {
        fail_file(path, "truncated GLB: no room for the JSON chunk (declared length " +
                            std::to_string(length) + ")");
    }
    std::size_t pos = 12;
    for (int chunk = 0; pos < length; chunk++) {
        if (length - pos < 8) {
            fail_file(path, "truncated GLB: chunk " + std::to_string(chunk) + " header at byte " +
                                std::to_string(pos) + " runs past the declared length " +
                                std::to_string(length));
        }
        const uint32_t chunk_length = read_u32le(bytes.data() + pos);
        const uint32_t chunk_type = read_u32le(bytes.data() + pos + 4);
        if (chunk == 0 && chunk_type != 0x4E4F534Au) { /* "JSON" */
            fail_file(path, "GLB: the first chunk is not JSON");
        }
        if (chunk_length > length - pos - 8) {
            fail_file(path, "truncated GLB: chunk " + std::to_string(chunk) + " at byte " +
                                std::to_string(pos) + " declares " + std::to_string(chunk_length) +
                                " bytes, only " + std::to_string(length - pos - 8) + " remain");
        }
        pos += 8 + std::size_t(chunk_length);
    }
    if (length < size) {
        notes.push_back("GLB: " + std::to_string(size - length) +
                        " bytes after the declared length ignored");
    }
    return length;
}

/* A JSON glTF starts with '{' after an optional UTF-8 byte order mark and
 * white space; anything else is not worth handing to a JSON parser. */
bool looks_like_json_object(const std::vector<unsigned char> &bytes) {
    std::size_t i = 0;
    if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) {
        i = 3;
    }
    while (i < bytes.size() &&
           (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\n' || bytes[i] == '\r')) {
        i++;
    }
    return i < bytes.size() && bytes[i] == '{';
}

void add_tinygltf_lines(const std::string &text, std::vector<std::string> &notes) {
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) {
            end = text.size();
        }
        if (end > start) {
            notes.push_back("tinygltf: " + printable_text(text.substr(start, end - start)));
        }
        start = end + 1;
    }
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) {
        s.pop_back();
    }
    return s;
}

/* For options.external_files = false: no file exists. */
bool no_file_exists(const std::string &, void *) { return false; }
bool no_file_read(std::vector<unsigned char> *, std::string *err, const std::string &name, void *) {
    if (err) *err += "external file " + name + " refused (external files are off)\n";
    return false;
}

} // namespace

[[noreturn]] void fail_file(const std::string &path, const std::string &problem) {
    throw GltfError(printable_text(path, kGltfMaxQuotedBytes) + ": " +
                    printable_text(problem, kMaxMessageBytes));
}

/* The whole file. Read here rather than by tinygltf so that a missing or
 * unreadable file is one clear error, and so that the bytes are checked
 * (GLB layout) before tinygltf sees them. */
std::vector<unsigned char> read_file(const std::string &path) {
    errno = 0;
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"),
                                                          &std::fclose);
    if (!file) {
        fail_file(path, std::string("cannot open: ") + std::strerror(errno));
    }
    std::vector<unsigned char> bytes;
    unsigned char chunk[1 << 16];
    for (;;) {
        const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
        bytes.insert(bytes.end(), chunk, chunk + n);
        if (bytes.size() > UINT_MAX) {
            fail_file(path, "file is 4 GiB or larger (tinygltf reads at most 2^32 - 1 bytes)");
        }
        if (n < sizeof chunk) {
            break;
        }
    }
    if (std::ferror(file.get())) {
        fail_file(path, std::string("cannot read: ") + std::strerror(errno));
    }
    if (bytes.empty()) {
        fail_file(path, "empty file (not a glTF file)");
    }
    return bytes;
}

/* Parses the file with tinygltf: GLB or JSON by the magic, external
 * buffers relative to the file's folder. */
tinygltf::Model parse_gltf(const std::string &path, const std::vector<unsigned char> &bytes,
                           bool external_files, std::vector<std::string> &notes) {
    if (bytes.empty()) {
        fail_file(path, "empty file (not a glTF file)");
    }
    if (bytes.size() > UINT_MAX) {
        fail_file(path, "file is 4 GiB or larger (tinygltf reads at most 2^32 - 1 bytes)");
    }
    std::string base_dir = std::filesystem::path(path).parent_path().string();
    if (base_dir.empty()) {
        base_dir = ".";
    }

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&ignore_image, nullptr);
    if (!external_files) {
        parser.SetFsCallbacks({&no_file_exists, &tinygltf::ExpandFilePath, &no_file_read,
                               &tinygltf::WriteWholeFile, nullptr});
    }
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        if (has_glb_magic(bytes)) {
            const uint32_t length = check_glb_layout(path, bytes, notes);
            /* check_glb_layout: the JSON chunk (header at 12) lies within length */
            check_json_depth(path, bytes.data() + 20, read_u32le(bytes.data() + 12), 20,
                             "the GLB's JSON chunk");
            ok = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), length, base_dir);
        } else if (looks_like_json_object(bytes)) {
            check_json_depth(path, bytes.data(), bytes.size(), 0, "the JSON");
            ok = parser.LoadASCIIFromString(&model, &err, &warn,
                                            reinterpret_cast<const char *>(bytes.data()),
                                            static_cast<unsigned int>(bytes.size()), base_dir);
        } else {
            fail_file(path, "not a glTF file (neither the GLB magic \"glTF\" nor a JSON object)");
        }
    } catch (const GltfError &) {
        throw;
    } catch (const std::exception &e) {
        fail_file(path, std::string("tinygltf failed: ") + e.what());
    }
    add_tinygltf_lines(warn, notes);
    if (!ok) {
        /* tinygltf echoes input (a whole data: URI, bytes that are not
         * UTF-8): each of its lines quoted within the bound. */
        std::string text;
        std::vector<std::string> lines;
        add_tinygltf_lines(trimmed(err), lines);
        for (const std::string &line : lines) {
            text += (text.empty() ? "" : "; ") + line.substr(std::strlen("tinygltf: "));
        }
        fail_file(path, "tinygltf: " + (text.empty() ? std::string("failed") : text));
    }
    /* tinygltf sometimes reports a problem and goes on (e.g. a buffer
     * without uri in a JSON file); what it loaded is still range-checked
     * later (gltf_accessors.cpp), so keep its words as a note. */
    add_tinygltf_lines(err, notes);
    return model;
}

} // namespace gltf_detail
} // namespace sv
