// albedo_tables_main.cpp: `idk_albedo_tables OUT.h` writes shared/pt_albedo_tables.h, the directional-albedo
// tables of the path tracer's energy compensation, from the CPU integrator (pathtrace/albedo_integrator.cpp).
// Regenerate with: build/bin/idk_albedo_tables shaders_glsl/shared/pt_albedo_tables.h
#include <cstdio>
#include <fstream>

#include "pathtrace/albedo_integrator.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: idk_albedo_tables OUT.h\n");
        return 2;
    }
    const std::string text = idk::pathtrace::albedoTablesHeader(
        idk::pathtrace::computeAlbedoTables(idk::pathtrace::kAlbedoTableStrata));
    std::ofstream out(argv[1], std::ios::binary);
    out << text;
    if (!out) {
        std::fprintf(stderr, "idk_albedo_tables: cannot write %s\n", argv[1]);
        return 1;
    }
    return 0;
}
