// SPDX-License-Identifier: BSD-3-Clause
// tinygltf's implementation compiled from Debian's header (libtinygltf-dev, 2.7.0) with this
// build's flags, used instead of Debian's shared libtinygltf when
// NORMALMAPPING_TINYGLTF_FROM_SOURCE is on (scripts/sanitize.sh): the sanitizers then check
// tinygltf's own memory accesses, and libFuzzer sees its branches. Same configuration as
// Debian's build: nlohmann/json and stb_image (the stb implementation comes from libstb).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
