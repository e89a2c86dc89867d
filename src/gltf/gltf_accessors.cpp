/*
 * The glTF loader's accessor decoder: every component of an accessor as a
 * double, after checking its format against what its use accepts and every
 * byte range it reads (the bufferView inside its buffer, the elements
 * inside the bufferView, both halves of a sparse accessor), and bounding
 * what it allocates before it allocates it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gltf_detail.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace sv {
namespace gltf_detail {

namespace {

/* A sparse accessor without bufferView has zeros for a base: nothing in the
 * file pays for its count, so it gets a tighter bound (16M components,
 * 128 MB of doubles: 5.6M VEC3 positions). */
constexpr std::size_t kMaxUnbackedComponents = std::size_t(1) << 24;

bool checked_add(std::size_t a, std::size_t b, std::size_t *sum) {
    if (a > SIZE_MAX - b) {
        return false;
    }
    *sum = a + b;
    return true;
}

bool checked_mul(std::size_t a, std::size_t b, std::size_t *product) {
    if (a != 0 && b > SIZE_MAX / a) {
        return false;
    }
    *product = a * b;
    return true;
}

/* One component as a double. Every component type an AccessorFormat
 * accepts (u8, u16, u32, float) is exact in a double, so one decoder serves
 * indices, joints, weights, positions and matrices. Normalized integers
 * follow glTF 2.0 section 3.11 (c / 255, c / 65535; signed: max(c / 127,
 * -1), max(c / 32767, -1)). */
double read_component(const unsigned char *p, int component_type, bool normalized) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        uint8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    default: return 0.0; /* unreachable: AccessorFormat admits none other */
    }
}

} // namespace

const Accessor &Loader::accessor_at(int index, const std::string &who) const {
    if (index < 0 || index >= static_cast<int>(gltf_.accessors.size())) {
        fail(who + ": accessor " + std::to_string(index) + " does not exist (" +
             std::to_string(gltf_.accessors.size()) + " accessors)");
    }
    return gltf_.accessors[index];
}

/* The address of element 0 of `count` elements of element_size bytes, at
 * byte_offset in bufferView view_index, after checking that all of them lie
 * inside the bufferView and the bufferView inside its buffer. *stride gets
 * the distance between elements: the bufferView's byteStride when
 * use_view_stride and it is set, else element_size (tightly packed).
 * count >= 1 (the callers check). */
const unsigned char *Loader::element_span(int view_index, std::size_t byte_offset,
                                          std::size_t count, std::size_t element_size,
                                          bool use_view_stride, const std::string &who,
                                          std::size_t *stride) const {
    if (view_index < 0 || view_index >= static_cast<int>(gltf_.bufferViews.size())) {
        fail(who + ": bufferView " + std::to_string(view_index) + " does not exist (" +
             std::to_string(gltf_.bufferViews.size()) + " bufferViews)");
    }
    const tinygltf::BufferView &view = gltf_.bufferViews[view_index];
    const std::string view_name = "bufferView " + std::to_string(view_index);
    if (view.buffer < 0 || view.buffer >= static_cast<int>(gltf_.buffers.size())) {
        fail(who + ": " + view_name + ": buffer " + std::to_string(view.buffer) +
             " does not exist (" + std::to_string(gltf_.buffers.size()) + " buffers)");
    }
    const std::vector<unsigned char> &data = gltf_.buffers[view.buffer].data;
    std::size_t view_end;
    if (!checked_add(view.byteOffset, view.byteLength, &view_end) || view_end > data.size()) {
        fail(who + ": " + view_name + " (bytes " + std::to_string(view.byteOffset) + " + " +
             std::to_string(view.byteLength) + ") runs past the end of buffer " +
             std::to_string(view.buffer) + " (" + std::to_string(data.size()) +
             " bytes): truncated or missing buffer data");
    }
    *stride = element_size;
    if (use_view_stride && view.byteStride != 0) {
        if (view.byteStride < element_size) {
            fail(who + ": " + view_name + " byteStride " + std::to_string(view.byteStride) +
                 " is smaller than the element (" + std::to_string(element_size) + " bytes)");
        }
        *stride = view.byteStride;
    }
    if (byte_offset >= view.byteLength) {
        fail(who + ": byteOffset " + std::to_string(byte_offset) + " is past the end of " +
             view_name + " (" + std::to_string(view.byteLength) + " bytes)");
    }
    /* byte_offset + stride * (count - 1) + element_size <= byteLength */
    std::size_t span, end;
    if (!checked_mul(*stride, count - 1, &span) || !checked_add(span, element_size, &span) ||
        !checked_add(byte_offset, span, &end) || end > view.byteLength) {
        fail(who + ": " + std::to_string(count) + " elements of " + std::to_string(element_size) +
             " bytes, stride " + std::to_string(*stride) + ", at byteOffset " +
             std::to_string(byte_offset) + " run past the end of " + view_name + " (" +
             std::to_string(view.byteLength) + " bytes)");
    }
    return data.data() + view.byteOffset + byte_offset;
}

/* Checks a sparse accessor's counts, types and both byte ranges (before
 * the accessor's values are allocated); apply_sparse then reads them. */
void Loader::check_sparse_ranges(const Accessor &a, const std::string &who) const {
    std::vector<double> none;
    apply_sparse(a, who, none, false);
}

/* Writes a sparse accessor's values over the base values (WRITE false:
 * only the checks of the ranges). */
void Loader::apply_sparse(const Accessor &a, const std::string &who, std::vector<double> &values,
                          bool write) const {
    const std::string sparse_who = who + " (sparse)";
    const int sparse_count = a.sparse.count;
    if (sparse_count < 1 || std::size_t(sparse_count) > a.count) {
        fail(sparse_who + ": count " + std::to_string(sparse_count) + " is not in 1.." +
             std::to_string(a.count));
    }
    const int index_type = a.sparse.indices.componentType;
    if (index_type != kU8 && index_type != kU16 && index_type != kU32) {
        fail(sparse_who + ": indices are " + component_type_name(index_type) +
             ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    }
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) {
        fail(sparse_who + ": negative byteOffset");
    }
    const std::size_t count = std::size_t(sparse_count);
    const std::size_t components = components_in(a.type);
    const std::size_t value_size = components * component_size(a.componentType);
    std::size_t index_stride, value_stride;
    const unsigned char *index_bytes = element_span(a.sparse.indices.bufferView,
                                                    std::size_t(a.sparse.indices.byteOffset), count,
                                                    component_size(index_type), false,
                                                    sparse_who + " indices", &index_stride);
    const unsigned char *value_bytes = element_span(a.sparse.values.bufferView,
                                                    std::size_t(a.sparse.values.byteOffset), count,
                                                    value_size, false, sparse_who + " values",
                                                    &value_stride);
    if (!write) {
        return;
    }
    const std::size_t csize = component_size(a.componentType);
    for (std::size_t i = 0; i < count; i++) {
        const double target = read_component(index_bytes + i * index_stride, index_type, false);
        if (!(target < double(a.count))) {
            fail(sparse_who + ": index " + std::to_string(i) + " is " +
                 std::to_string(static_cast<uint64_t>(target)) +
                 ", not below the accessor's count " + std::to_string(a.count));
        }
        const std::size_t element = static_cast<std::size_t>(target);
        for (std::size_t c = 0; c < components; c++) {
            values[element * components + c] = read_component(value_bytes + i * value_stride +
                                                                  c * csize,
                                                              a.componentType, a.normalized);
        }
    }
}

/* Every component of accessor `index`, count * components values, after
 * checking its format against `format` and every byte range it reads. */
std::vector<double> Loader::decode(int index, const AccessorFormat &format,
                                   const std::string &who) const {
    const Accessor &a = accessor_at(index, who);
    const std::string label = who + " (accessor " + std::to_string(index) + ")";

    bool format_ok = a.type == format.type;
    if (format_ok) {
        format_ok = false;
        for (int i = 0; i < format.num_allowed; i++) {
            if (a.componentType == format.allowed[i].component_type &&
                a.normalized == format.allowed[i].normalized) {
                format_ok = true;
            }
        }
    }
    if (!format_ok) {
        fail(label + " is " + (a.normalized ? "normalized " : "") +
             component_type_name(a.componentType) + " " + type_name(a.type) + ", expected " +
             format.expected);
    }
    if (a.count == 0) {
        fail(label + ": count is 0");
    }
    const std::size_t components = components_in(a.type);
    const std::size_t csize = component_size(a.componentType);
    std::size_t total;
    if (!checked_mul(a.count, components, &total) || total > kMaxAccessorComponents) {
        fail(label + ": count " + std::to_string(a.count) + " is too large (more than " +
             std::to_string(kMaxAccessorComponents) + " components)");
    }

    if (a.bufferView < 0 && !a.sparse.isSparse) {
        fail(label + " has no bufferView (and is not sparse)");
    }
    if (a.bufferView < 0 && total > kMaxUnbackedComponents) {
        fail(label + ": sparse, without bufferView, and count " + std::to_string(a.count) +
             " is too large (more than " + std::to_string(kMaxUnbackedComponents) +
             " components of zeros)");
    }
    /* The range first, then the allocation: a 380-byte file claiming 89M
     * VEC3 elements must fail here, not after allocating 2 GB. */
    std::size_t stride = 0;
    const unsigned char *first = nullptr;
    if (a.bufferView >= 0) {
        first = element_span(a.bufferView, a.byteOffset, a.count, components * csize, true, label,
                             &stride);
    }
    if (a.sparse.isSparse) {
        check_sparse_ranges(a, label);
    }
    std::vector<double> values(total, 0.0);
    if (a.bufferView >= 0) {
        for (std::size_t e = 0; e < a.count; e++) {
            const unsigned char *element = first + e * stride;
            for (std::size_t c = 0; c < components; c++) {
                values[e * components + c] = read_component(element + c * csize, a.componentType,
                                                            a.normalized);
            }
        }
    }
    if (a.sparse.isSparse) {
        apply_sparse(a, label, values);
    }
    return values;
}

} // namespace gltf_detail
} // namespace sv
