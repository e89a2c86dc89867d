/*
 * The one translation unit that compiles tinygltf (Debian's libtinygltf-dev
 * ships it as a header). Image decoding and writing are off: shadowvol reads
 * positions and indices only, and a malformed image must not be able to
 * fail (or crash) a model load.
 */
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
