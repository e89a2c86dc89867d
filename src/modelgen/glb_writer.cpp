// A small glTF 2.0 binary (.glb) writer: 12-byte header ('glTF', version 2,
// total length), a JSON chunk padded with spaces to 4 bytes, a BIN chunk
// padded with zeros. No third-party code.

#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "model_gen.h"

namespace svgen {
namespace {

void put_u32(std::vector<std::uint8_t> &out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// A float32 as a JSON number that reads back as the same float32.
std::string number(float f) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(f));
    return buf;
}

} // namespace

std::vector<std::uint8_t> write_glb(const TriMesh &mesh, const std::string &name) {
    const std::size_t nv = mesh.num_vertices();
    if (nv == 0 || mesh.indices.empty() || mesh.indices.size() % 3 != 0)
        throw std::invalid_argument("write_glb: empty mesh or index count not a multiple of 3");
    for (float f : mesh.positions)
        if (!(f == f) || f == std::numeric_limits<float>::infinity() ||
            f == -std::numeric_limits<float>::infinity())
            throw std::invalid_argument("write_glb: non-finite position");
    for (std::uint32_t i : mesh.indices)
        if (i >= nv) throw std::invalid_argument("write_glb: index out of range");

    // Unsigned short indices while every index fits below 65535 (the
    // primitive-restart value), else unsigned int.
    const bool u16 = nv <= 65535;
    std::vector<std::uint8_t> bin;
    bin.resize(mesh.positions.size() * 4);
    std::memcpy(bin.data(), mesh.positions.data(), bin.size()); // x86-64: little-endian
    const std::size_t positions_bytes = bin.size();
    for (std::uint32_t i : mesh.indices) {
        bin.push_back(static_cast<std::uint8_t>(i));
        bin.push_back(static_cast<std::uint8_t>(i >> 8));
        if (!u16) {
            bin.push_back(static_cast<std::uint8_t>(i >> 16));
            bin.push_back(static_cast<std::uint8_t>(i >> 24));
        }
    }
    const std::size_t indices_bytes = bin.size() - positions_bytes;
    while (bin.size() % 4) bin.push_back(0);

    float lo[3], hi[3];
    for (int c = 0; c < 3; ++c) lo[c] = hi[c] = mesh.positions[std::size_t(c)];
    for (std::size_t v = 0; v < nv; ++v)
        for (int c = 0; c < 3; ++c) {
            const float f = mesh.positions[3 * v + std::size_t(c)];
            if (f < lo[c]) lo[c] = f;
            if (f > hi[c]) hi[c] = f;
        }

    std::string j;
    j += "{\"asset\":{\"version\":\"2.0\",\"generator\":\"shadowvol generate_models "
         "(tools/generate_models)\"},";
    j += "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],";
    j += "\"nodes\":[{\"mesh\":0,\"name\":\"" + name + "\"}],";
    j += "\"meshes\":[{\"name\":\"" + name +
         "\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}],";
    j += "\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + "}],";
    j += "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" +
         std::to_string(positions_bytes) +
         ",\"target\":34962},{\"buffer\":0,\"byteOffset\":" + std::to_string(positions_bytes) +
         ",\"byteLength\":" + std::to_string(indices_bytes) + ",\"target\":34963}],";
    j += "\"accessors\":[{\"bufferView\":0,\"byteOffset\":0,\"componentType\":5126,\"count\":" +
         std::to_string(nv) + ",\"type\":\"VEC3\",\"min\":[" + number(lo[0]) + "," + number(lo[1]) +
         "," + number(lo[2]) + "],\"max\":[" + number(hi[0]) + "," + number(hi[1]) + "," +
         number(hi[2]) + "]},";
    j += "{\"bufferView\":1,\"byteOffset\":0,\"componentType\":" +
         std::string(u16 ? "5123" : "5125") + ",\"count\":" + std::to_string(mesh.indices.size()) +
         ",\"type\":\"SCALAR\"}]}";
    while (j.size() % 4) j += ' ';

    const std::size_t total = 12 + 8 + j.size() + 8 + bin.size();
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("write_glb: file over 4 GiB");
    std::vector<std::uint8_t> out;
    out.reserve(total);
    put_u32(out, 0x46546C67u); // "glTF"
    put_u32(out, 2);
    put_u32(out, static_cast<std::uint32_t>(total));
    put_u32(out, static_cast<std::uint32_t>(j.size()));
    put_u32(out, 0x4E4F534Au); // "JSON"
    out.insert(out.end(), j.begin(), j.end());
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, 0x004E4942u); // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

} // namespace svgen
