// fuzz_scene: the libFuzzer target for chapter 7's scene loader (preset `fuzz`).
// Every input is parsed as a scene file; bad input must end in exactpixels::Error and
// nothing else (no crash, no leak, no undefined behaviour, no other exception). A scene
// that loads and is small is also rendered, so the renderer sees odd scenes too.
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const exactpixels::Scene scene =
            exactpixels::parse_scene(text, "fuzz.toml", "/nonexistent-fuzz-folder");
        if (static_cast<long long>(scene.width) * scene.height <= 64 * 64) {
            (void)exactpixels::render_scene(scene);
        }
    } catch (const exactpixels::Error&) {
        // bad input, reported as it should be
    }
    return 0;
}
