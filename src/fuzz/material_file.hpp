// material_file.hpp: the MTL half of the model fuzz targets (fuzz_material,
// fuzz_mtl_numbers). An input is written as a material file into the folder of the
// fixture models, and a one-triangle OBJ text that names it is returned, for the target
// to add usemtl and face lines to.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace fuzz {

/// Writes `text` as the material file `TARGET-PID.material` in EXACTPIXELS_MODEL_FIXTURES
/// (not .mtl: the seed pattern must not pick a mutated file up on a later run), and
/// returns the start of an OBJ text: its mtllib line, three positions and three texture
/// coordinates.
inline std::string write_material_file(std::string_view text, const std::string& target) {
    const std::filesystem::path folder = EXACTPIXELS_MODEL_FIXTURES;
    const std::string name = target + "-" + std::to_string(::getpid()) + ".material";
    std::ofstream out(folder / name, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out.flush()) {
        std::fprintf(stderr, "%s: cannot write %s\n", target.c_str(), name.c_str());
        std::abort(); // the harness, not the reader, failed
    }
    return "mtllib " + name + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
}

} // namespace fuzz
