// make-models: writes the models chapter 7's scenes use into a folder (by default
// chapters/07-scenes/models/ of the source tree, where they are committed; the test
// "the committed models are what the generator makes" checks that they match).
// Usage: make-models [FOLDER]
#include "exactpixels/base/error.hpp"
#include "exactpixels/lab/model_generator.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

int main(int argc, char** argv) {
    const std::filesystem::path folder =
        argc > 1 ? argv[1] : EXACTPIXELS_SOURCE_DIR "/chapters/07-scenes/models";
    try {
        for (const auto& model : exactpixels::shipped_models()) {
            exactpixels::write_generated_model(model, folder);
            fmt::print("wrote {}\n", (folder / (model.name + ".obj")).string());
        }
    } catch (const exactpixels::Error& error) {
        fmt::print(stderr, "make-models: {}\n", error.what());
        return 2;
    }
    return 0;
}
