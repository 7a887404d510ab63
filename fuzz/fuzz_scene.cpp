// libFuzzer target: the scene reader, TOML to a checked Scene (docs/fuzzing.md).
#include "fuzz_input.h"
#include "scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_input::refused_or_read(data, size, ".toml",
                                       [](const std::string &path) { (void)armour::load_scene(path); });
}
