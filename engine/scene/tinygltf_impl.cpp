// tinygltf_impl.cpp: the single translation unit that compiles tinygltf's implementation (Debian ships it
// header-only), with the configuration from tinygltf_include.hpp.
#define TINYGLTF_IMPLEMENTATION
#include "scene/tinygltf_include.hpp"
