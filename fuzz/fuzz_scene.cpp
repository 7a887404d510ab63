// libFuzzer target: the scene reader, TOML to a checked Scene, with `--set`
// overrides (docs/fuzzing.md). A line "#set KEY=VALUE" of the input (a TOML
// comment, so the file reads the same) is passed as the override KEY=VALUE.
#include "fuzz_input.h"
#include "scene.h"

#include <sstream>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::vector<std::string> overrides;
    std::istringstream lines(std::string(reinterpret_cast<const char *>(data), size));
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("#set ", 0) == 0)
            overrides.push_back(line.substr(5));
    return fuzz_input::refused_or_read(
        data, size, ".toml", [&](const std::string &path) { (void)armour::load_scene(path, overrides); });
}
